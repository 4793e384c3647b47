// One entry point for every scene file a user has: the loader is chosen by the file's
// extension, and the import rules (import_options.h) are applied, so `radflux solve`,
// `radflux viewfactors` and the service read the same Scene from the same file.
#pragma once

#include <map>
#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/import_options.h"
#include "solver/scene/scene.h"

namespace radflux {

// The scene in `path` (.obj, .gltf, .glb, .mgf, .stl, .vs3; the extension picks the format,
// case-insensitively), with the import rules applied (import_rules.h; what they changed is
// in Scene::import_log). INVALID_ARGUMENT for an unknown extension, naming the ones
// supported, and for what the rules refuse. The result is not yet validated: see
// ValidateScene.
absl::StatusOr<Scene> LoadScene(const std::string& path, const ImportOptions& options);

// A scene as files in memory (an uploaded bundle): paths relative to the bundle's root,
// '/'-separated, to their bytes; `main` is the scene file's path among them.
struct SceneBundle {
  std::string main;
  std::map<std::string, std::string> files;
};

// The same as LoadScene on the bundle's files laid out on disk, except that only the
// bundle's files are read: a name that leads outside it (an MGF include or an mtllib with
// '..' past the root, an absolute path) or is not in it is read as a missing file.
// Messages name the files by their bundle paths.
absl::StatusOr<Scene> LoadSceneBundle(const SceneBundle& bundle, const ImportOptions& options);

}  // namespace radflux
