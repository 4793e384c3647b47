// The machine's physical memory, for defaults that scale with it (memory budgets).
#pragma once

#include <cstdint>

namespace radflux {

// Bytes of physical memory (sysconf), or 0 when the system does not say.
uint64_t PhysicalMemoryBytes();

}  // namespace radflux
