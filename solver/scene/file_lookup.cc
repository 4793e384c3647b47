#include "solver/scene/file_lookup.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_replace.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

bool IsFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

// The entry of folder `dir` named `part` ignoring case, or an empty path.
fs::path MatchEntry(const fs::path& dir, const std::string& part) {
  if (part == "." || part == "..") return dir / part;
  std::error_code ec;
  if (fs::exists(dir / part, ec)) return dir / part;
  const std::string wanted = absl::AsciiStrToLower(part);
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (absl::AsciiStrToLower(it->path().filename().string()) == wanted) return it->path();
  }
  return {};
}

}  // namespace

std::optional<std::string> FindFile(const std::string& dir, const std::string& name) {
  const fs::path relative(absl::StrReplaceAll(name, {{"\\", "/"}}));
  const fs::path base = relative.is_absolute() ? relative.root_path() : fs::path(dir);
  if (IsFile(base / relative.relative_path())) return (base / relative.relative_path()).string();
  fs::path found = base.empty() ? fs::path(".") : base;
  for (const fs::path& part : relative.relative_path()) {
    found = MatchEntry(found, part.string());
    if (found.empty()) return std::nullopt;
  }
  if (!IsFile(found)) return std::nullopt;
  return (base.empty() ? found.lexically_relative(".") : found).string();
}

absl::StatusOr<std::string> ReadFoundFile(const std::string& dir, const std::string& name) {
  const std::optional<std::string> found = FindFile(dir, name);
  if (!found) return absl::NotFoundError("no such file");
  std::ifstream in(*found, std::ios::binary);
  if (!in) return absl::NotFoundError("cannot open the file");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

const std::string* FindInFiles(const std::map<std::string, std::string>& files,
                               const std::string& path) {
  if (const auto it = files.find(path); it != files.end()) return &it->second;
  for (const auto& [candidate, bytes] : files) {
    if (absl::EqualsIgnoreCase(candidate, path)) return &bytes;
  }
  return nullptr;
}

}  // namespace radflux
