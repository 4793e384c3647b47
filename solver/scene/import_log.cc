#include "solver/scene/import_log.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace radflux {

namespace {

// `message` with each "{one|many}" picked by `count`.
std::string PickNumber(const std::string& message, uint64_t count) {
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

}  // namespace

std::string ImportFixup::Text() const {
  std::string text = PickNumber(message, count);
  if (share_of.empty()) return text;
  absl::StrAppend(&text, ": ", absl::StrFormat("%.0f%%", 100 * ShareMean()), " ",
                  PickNumber(share_of, count));
  if (count == 1) return text;
  return absl::StrCat(text, " on average, ", absl::StrFormat("%.0f%%", 100 * share_max),
                      " at most");
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

void ImportLog::AddShare(const std::string& kind, const std::string& message,
                         const std::string& where, double share, const std::string& share_of) {
  Add(kind, message, where);
  auto it = std::find_if(fixups_.begin(), fixups_.end(),
                         [&](const ImportFixup& f) { return f.kind == kind; });
  it->share_of = share_of;
  it->share_sum += share;
  it->share_max = std::max(it->share_max, share);
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
