// Wavefront OBJ + MTL loading through tinyobjloader. Kd is diffuse reflectance,
// Ke is emitted radiance L_e (so emission E = pi * Ke), map_Kd / map_Ke / map_d textures
// are applied per face as face_textures.h says. Object ('o') and group ('g') names are kept
// per face. The result is not yet validated: see ValidateScene.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/face_textures.h"
#include "solver/scene/scene.h"

namespace radflux {

// Loads `path`; materials are looked up beside it, textures relative to its folder (the
// exact name first, else ignoring case: FindFile). Errors name the file and line.
absl::StatusOr<Scene> LoadObjFile(const std::string& path);

// Loads OBJ text with its MTL text (used for uploaded scenes and fuzzing); `name`
// is used in messages. Textures are read through `textures` (none given: every texture
// is logged as not read and its material keeps its Kd/Ke).
absl::StatusOr<Scene> LoadObjText(const std::string& obj_text, const std::string& mtl_text,
                                  const std::string& name, const TextureReader& textures = {});

}  // namespace radflux
