#include "solver/scene/mtl_check.h"

#include <cmath>
#include <cstdlib>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

namespace radflux {
namespace {

// Whether `word` reads whole as a number that is NaN or infinite (1e999 included).
bool IsNonFiniteNumber(absl::string_view word) {
  const std::string text(word);
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && !text.empty() && !std::isfinite(value);
}

}  // namespace

absl::Status CheckMtlColours(std::string_view mtl_text, const std::string& name) {
  int number = 0;
  const absl::string_view text(mtl_text.data(), mtl_text.size());
  for (absl::string_view line : absl::StrSplit(text, '\n')) {
    ++number;
    std::vector<absl::string_view> words =
        absl::StrSplit(absl::StripAsciiWhitespace(line), absl::ByAnyChar(" \t"), absl::SkipEmpty());
    if (words.empty() || (words[0] != "Kd" && words[0] != "Ke")) continue;
    for (size_t k = 1; k < words.size(); ++k) {
      if (IsNonFiniteNumber(words[k])) {
        return absl::InvalidArgumentError(absl::StrCat(name, ":", number, ": ", words[0],
                                                       " value '", words[k],
                                                       "' is not a finite number"));
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace radflux
