#include "tests/integration/radfluxd_path.h"

namespace radflux::testing {

std::string RadfluxdPath() { return RADFLUXD_PATH; }

}  // namespace radflux::testing
