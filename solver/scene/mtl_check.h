// The checks on MTL text that tinyobjloader does not make: it reads a colour word it cannot
// parse ("nan", "inf") as 0, so a material with `Kd nan 0.5 0.5` or `Ke inf 1 1` would load
// as black or dark without a word.
#pragma once

#include <string>
#include <string_view>

#include "absl/status/status.h"

namespace radflux {

// OK when every number of every Kd and Ke line of `mtl_text` is finite; otherwise
// INVALID_ARGUMENT "NAME:LINE: Kd value 'nan' is not a finite number" for the first bad
// one (`name` names the MTL file in the message). Words that are not numbers at all are
// left to tinyobjloader, as before.
absl::Status CheckMtlColours(std::string_view mtl_text, const std::string& name);

}  // namespace radflux
