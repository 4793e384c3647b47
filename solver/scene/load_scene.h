// One entry point for every scene file a user has: the loader is chosen by the file's
// extension, and the import rules (import_options.h) are applied, so `radflux solve`,
// `radflux viewfactors` and the service read the same Scene from the same file.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/import_options.h"
#include "solver/scene/scene.h"

namespace radflux {

// The scene in `path` (.obj, .gltf, .glb, .mgf; the extension picks the format,
// case-insensitively), with the import rules applied (import_rules.h; what they changed is
// in Scene::import_log). INVALID_ARGUMENT for an unknown extension, naming the ones
// supported, and for what the rules refuse. The result is not yet validated: see
// ValidateScene.
absl::StatusOr<Scene> LoadScene(const std::string& path, const ImportOptions& options);

}  // namespace radflux
