#include "solver/scene/import_log.h"

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace radflux {

std::string ImportFixup::Text() const {
  std::string text;
  size_t at = 0;
  for (size_t open; (open = message.find('{', at)) != std::string::npos;) {
    const size_t bar = message.find('|', open);
    const size_t close = message.find('}', open);
    if (bar == std::string::npos || close == std::string::npos || bar > close) break;
    absl::StrAppend(&text, absl::string_view(message).substr(at, open - at),
                    count == 1 ? absl::string_view(message).substr(open + 1, bar - open - 1)
                               : absl::string_view(message).substr(bar + 1, close - bar - 1));
    at = close + 1;
  }
  absl::StrAppend(&text, absl::string_view(message).substr(at));
  return text;
}

void ImportLog::Add(const std::string& kind, const std::string& message, const std::string& where,
                    uint64_t count) {
  auto it = std::find_if(fixups_.begin(), fixups_.end(),
                         [&](const ImportFixup& f) { return f.kind == kind; });
  if (it == fixups_.end()) {
    fixups_.push_back({kind, message, count, where});
  } else {
    it->count += count;
  }
}

std::vector<std::string> ImportLog::Lines() const {
  std::vector<std::string> lines;
  for (const ImportFixup& f : fixups_) {
    lines.push_back(absl::StrCat("import: ", f.count, " ", f.Text(),
                                 f.first.empty() ? "" : absl::StrCat(" (first at ", f.first, ")")));
  }
  return lines;
}

}  // namespace radflux
