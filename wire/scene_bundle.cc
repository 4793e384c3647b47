#include "wire/scene_bundle.h"

#include <openssl/evp.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "solver/scene/scene_references.h"
#include "wire/scene_hash.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

absl::Status BadPath(const std::string& path, const std::string& why) {
  return absl::InvalidArgumentError(absl::StrCat("bundle path '", path, "' ", why));
}

absl::StatusOr<std::string> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat(path, ": cannot open the file"));
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The deepest folder that holds every path of `paths` (absolute, normalised).
fs::path CommonFolder(const std::vector<fs::path>& paths) {
  fs::path common = paths[0].parent_path();
  for (const fs::path& p : paths) {
    while (common.has_relative_path() && *p.lexically_relative(common).begin() == "..") {
      common = common.parent_path();
    }
  }
  return common;
}

}  // namespace

absl::Status CheckBundlePath(const std::string& path) {
  if (path.empty()) return absl::InvalidArgumentError("a bundle path is empty");
  if (path.front() == '/') {
    return BadPath(path, "is absolute (a path must be relative to the bundle's root)");
  }
  if (path.find('\\') != std::string::npos || path.find('\0') != std::string::npos) {
    return BadPath(path, "has a backslash or a NUL (parts are separated by '/')");
  }
  for (absl::string_view part : absl::StrSplit(path, '/')) {
    if (part == "..") {
      return BadPath(path, "escapes the bundle (a path must be relative, without '..')");
    }
    if (part.empty() || part == ".") return BadPath(path, "has an empty or '.' part");
  }
  return absl::OkStatus();
}

absl::Status CheckBundlePaths(const std::vector<std::string>& paths) {
  if (paths.empty()) return absl::InvalidArgumentError("a bundle has no files");
  std::set<std::string> seen;
  for (const std::string& path : paths) {
    if (absl::Status s = CheckBundlePath(path); !s.ok()) return s;
    if (!seen.insert(path).second) return BadPath(path, "is given twice");
  }
  return absl::OkStatus();
}

std::string BundleContentHash(const std::vector<BundleFile>& files) {
  std::vector<const BundleFile*> order;
  for (const BundleFile& file : files) order.push_back(&file);
  if (!order.empty()) {
    std::sort(order.begin() + 1, order.end(),
              [](const BundleFile* a, const BundleFile* b) { return a->path < b->path; });
  }
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr);
  const auto update = [&](std::string_view bytes) {
    EVP_DigestUpdate(ctx.get(), bytes.data(), bytes.size());
  };
  update("radflux-bundle-v1\n");
  for (const BundleFile* file : order) {
    update(absl::StrCat(file->path, "\n", file->data.size(), "\n"));
    update(file->data);
  }
  return DigestHex(ctx.get());
}

absl::StatusOr<std::vector<BundleFile>> ReadSceneBundle(const std::string& path) {
  absl::StatusOr<std::vector<std::string>> named = SceneReferences(path);
  if (!named.ok()) return named.status();
  std::vector<fs::path> paths = {fs::absolute(path).lexically_normal()};
  for (const std::string& p : *named) {
    const fs::path normal = fs::absolute(p).lexically_normal();
    if (std::find(paths.begin(), paths.end(), normal) == paths.end()) paths.push_back(normal);
  }
  const fs::path root = CommonFolder(paths);
  std::vector<BundleFile> files;
  for (const fs::path& p : paths) {
    absl::StatusOr<std::string> data = ReadBytes(p.string());
    if (!data.ok()) return data.status();
    files.push_back({p.lexically_relative(root).generic_string(), *std::move(data)});
  }
  return files;
}

}  // namespace radflux
