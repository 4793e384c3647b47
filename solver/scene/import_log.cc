#include "solver/scene/import_log.h"

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace radflux {

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
    lines.push_back(absl::StrCat("import: ", f.count, " ", f.message,
                                 f.first.empty() ? "" : absl::StrCat(" (first at ", f.first, ")")));
  }
  return lines;
}

}  // namespace radflux
