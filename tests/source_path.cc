#include "tests/source_path.h"

namespace radflux::testing {

std::string SourcePath(std::string_view relative) {
  return std::string(RADFLUX_SOURCE_DIR "/").append(relative);
}

}  // namespace radflux::testing
