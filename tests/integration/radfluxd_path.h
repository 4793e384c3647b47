// The radfluxd executable the integration tests start, compiled into one small library
// (radfluxd_path.cc) so that the other test sources carry no checkout-specific path.
#pragma once

#include <string>

namespace radflux::testing {

// The absolute path of the radfluxd built beside these tests.
std::string RadfluxdPath();

}  // namespace radflux::testing
