// Progress reporting and cancellation shared by every long phase.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>

namespace radflux {

// Called with (phase, done, total) as work completes; returning false asks the
// computation to stop at the next safe point (Embree's convention).
using PhaseProgress = std::function<bool(std::string_view phase, int64_t done, int64_t total)>;

}  // namespace radflux
