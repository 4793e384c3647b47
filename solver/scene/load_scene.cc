#include "solver/scene/load_scene.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "absl/strings/str_split.h"
#include "solver/scene/file_lookup.h"
#include "solver/scene/gltf_loader.h"
#include "solver/scene/import_rules.h"
#include "solver/scene/mgf_loader.h"
#include "solver/scene/obj_loader.h"
#include "solver/scene/stl_loader.h"
#include "solver/scene/vs3_loader.h"

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

absl::Status UnknownFormat(const std::string& path) {
  return absl::InvalidArgumentError(
      absl::StrCat(path, ": unknown scene format '", Extension(path),
                   "' (supported: .obj, .gltf, .glb, .mgf, .stl, .vs3)"));
}

absl::StatusOr<Scene> SceneOfVs3(absl::StatusOr<Vs3Model> model) {
  if (!model.ok()) return model.status();
  return std::move(model->scene);
}

// The scene in `path` as its format's loader reads it, before the import rules.
absl::StatusOr<Scene> LoadByExtension(const std::string& path, const ImportOptions& options) {
  const std::string ext = Extension(path);
  if (ext == "obj") return LoadObjFile(path);
  if (ext == "gltf" || ext == "glb") return LoadGltfFile(path, options);
  if (ext == "mgf") return LoadMgfFile(path, options);
  if (ext == "stl") return LoadStlFile(path);
  if (ext == "vs3") return SceneOfVs3(LoadVs3File(path));
  return UnknownFormat(path);
}

// `name` as named from the bundle file `from`: joined to its folder, normalised.
std::string BundlePath(const std::string& from, const std::string& name) {
  return (std::filesystem::path(from).parent_path() / name).lexically_normal().generic_string();
}

// The bundle's files below the folder of `main`, keyed relative to it.
std::map<std::string, std::string> FilesBeside(const SceneBundle& bundle) {
  const std::string folder = std::filesystem::path(bundle.main).parent_path().generic_string();
  const std::string prefix = folder.empty() ? "" : folder + "/";
  std::map<std::string, std::string> files;
  for (const auto& [path, bytes] : bundle.files) {
    if (absl::StartsWith(path, prefix)) files.emplace(path.substr(prefix.size()), bytes);
  }
  return files;
}

// The MTL texts an OBJ names (mtllib lines), concatenated: what tinyobjloader reads beside
// an OBJ file on disk, each library in turn.
std::string BundleMtl(const SceneBundle& bundle, const std::string& obj) {
  std::string mtl;
  for (absl::string_view line : absl::StrSplit(obj, '\n')) {
    line = absl::StripAsciiWhitespace(line);
    if (!absl::ConsumePrefix(&line, "mtllib") || line.empty() || !absl::ascii_isspace(line[0])) {
      continue;
    }
    for (absl::string_view name : absl::StrSplit(line, ' ', absl::SkipWhitespace())) {
      const auto it = bundle.files.find(BundlePath(bundle.main, std::string(name)));
      if (it != bundle.files.end()) absl::StrAppend(&mtl, it->second, "\n");
    }
  }
  return mtl;
}

// The texture `name` (as an MTL names it, relative to the OBJ) from the bundle: the exact
// path first, else the one that matches ignoring case ('\\' read as '/'), as FindFile does
// on disk.
TextureReader BundleTextures(const SceneBundle& bundle) {
  return [&bundle](const std::string& name) -> absl::StatusOr<std::string> {
    const std::string path = BundlePath(bundle.main, absl::StrReplaceAll(name, {{"\\", "/"}}));
    if (const std::string* bytes = FindInFiles(bundle.files, path)) return *bytes;
    return absl::NotFoundError("no such file in the bundle");
  };
}

// LoadByExtension on a bundle.
absl::StatusOr<Scene> LoadBundleByExtension(const SceneBundle& bundle,
                                            const ImportOptions& options) {
  const auto main = bundle.files.find(bundle.main);
  if (main == bundle.files.end()) {
    return absl::InvalidArgumentError(absl::StrCat(bundle.main, ": not in the bundle"));
  }
  const std::string& bytes = main->second;
  const std::string ext = Extension(bundle.main);
  if (ext == "obj") {
    return LoadObjText(bytes, BundleMtl(bundle, bytes), bundle.main, BundleTextures(bundle));
  }
  if (ext == "gltf" || ext == "glb") {
    return LoadGltfData(bytes, bundle.main, options, FilesBeside(bundle));
  }
  if (ext == "mgf") {
    return LoadMgfText(bytes, bundle.main, options, MgfReaderFromMap(bundle.files));
  }
  if (ext == "stl") {
    const auto groups = bundle.files.find(bundle.main + ".groups");
    return LoadStlBytes(
        bytes, bundle.main,
        groups == bundle.files.end() ? std::nullopt : std::optional<std::string>(groups->second));
  }
  if (ext == "vs3") return SceneOfVs3(LoadVs3Text(bytes, bundle.main));
  return UnknownFormat(bundle.main);
}

absl::StatusOr<Scene> WithImportRules(absl::StatusOr<Scene> scene, const ImportOptions& options) {
  if (!scene.ok()) return scene.status();
  if (absl::Status s = ApplyImportRules(options, *scene); !s.ok()) return s;
  return scene;
}

}  // namespace

absl::StatusOr<Scene> LoadScene(const std::string& path, const ImportOptions& options) {
  return WithImportRules(LoadByExtension(path, options), options);
}

absl::StatusOr<Scene> LoadSceneBundle(const SceneBundle& bundle, const ImportOptions& options) {
  return WithImportRules(LoadBundleByExtension(bundle, options), options);
}

}  // namespace radflux
