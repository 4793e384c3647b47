#include "solver/scene/load_scene.h"

#include <algorithm>
#include <cctype>

#include "absl/strings/str_cat.h"
#include "solver/scene/gltf_loader.h"
#include "solver/scene/import_rules.h"
#include "solver/scene/mgf_loader.h"
#include "solver/scene/obj_loader.h"

namespace radflux {
namespace {

// The lower-case extension of `path` without its dot, "" if none.
std::string Extension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The scene in `path` as its format's loader reads it, before the import rules.
absl::StatusOr<Scene> LoadByExtension(const std::string& path, const ImportOptions& options) {
  const std::string ext = Extension(path);
  if (ext == "obj") return LoadObjFile(path);
  if (ext == "gltf" || ext == "glb") return LoadGltfFile(path, options);
  if (ext == "mgf") return LoadMgfFile(path, options);
  return absl::InvalidArgumentError(absl::StrCat(
      path, ": unknown scene format '", ext, "' (supported: .obj, .gltf, .glb, .mgf)"));
}

}  // namespace

absl::StatusOr<Scene> LoadScene(const std::string& path, const ImportOptions& options) {
  absl::StatusOr<Scene> scene = LoadByExtension(path, options);
  if (!scene.ok()) return scene.status();
  if (absl::Status s = ApplyImportRules(options, *scene); !s.ok()) return s;
  return scene;
}

}  // namespace radflux
