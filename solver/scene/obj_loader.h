// Wavefront OBJ + MTL loading through tinyobjloader. Kd is diffuse reflectance,
// Ke is emitted radiance L_e (so emission E = pi * Ke). Object ('o') and group ('g')
// names are kept per face. The result is not yet validated: see ValidateScene.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/scene.h"

namespace radflux {

// Loads `path`; materials are looked up beside it. Errors name the file and line.
absl::StatusOr<Scene> LoadObjFile(const std::string& path);

// Loads OBJ text with its MTL text (used for uploaded scenes and fuzzing); `name`
// is used in messages.
absl::StatusOr<Scene> LoadObjText(const std::string& obj_text, const std::string& mtl_text,
                                  const std::string& name);

}  // namespace radflux
