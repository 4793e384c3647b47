#include "solver/scene/import_options.h"

#include <cmath>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

namespace radflux {

absl::StatusOr<std::pair<std::string, Rgb>> ParseEmitRule(const std::string& value) {
  const size_t equals = value.rfind('=');
  const auto bad = [&] {
    return absl::InvalidArgumentError(
        absl::StrCat("--emit '", value,
                     "': expected MATERIAL=R,G,B (emitted radiance L_e, three numbers >= 0)"));
  };
  if (equals == std::string::npos || equals == 0) return bad();
  const std::vector<std::string> parts = absl::StrSplit(value.substr(equals + 1), ',');
  if (parts.size() != 3) return bad();
  Rgb radiance{};
  for (int b = 0; b < kBands; ++b) {
    if (!absl::SimpleAtod(parts[b], &radiance[b]) || !std::isfinite(radiance[b]) ||
        radiance[b] < 0) {
      return bad();
    }
  }
  return std::make_pair(value.substr(0, equals), radiance);
}

}  // namespace radflux
