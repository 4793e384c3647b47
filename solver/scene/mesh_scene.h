// A scene given as arrays instead of OBJ + MTL text (a structured upload), turned into the
// same Scene the OBJ loader makes: the same positions, faces, materials (reflectance as
// Kd, emission E = pi * L_e as from Ke) and object/group names interned in face order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/scene/scene.h"

namespace radflux {

struct MeshMaterialInput {
  std::string name;
  Rgb reflectance{};       // diffuse reflectance rho per band, in [0, 1) (OBJ: Kd)
  Rgb emitted_radiance{};  // L_e per band, W/(m^2 sr) (OBJ: Ke); emission E = pi * L_e
  double opacity = 1;      // Material::opacity, in (0, 1]
};

struct MeshFaceInput {
  std::vector<uint32_t> vertices;  // indices into MeshInput vertices, counter-clockwise
  uint32_t material = 0;           // index into MeshInput::materials
  std::string object, group;       // 'o' and 'g' names, may be empty
};

struct MeshInput {
  std::vector<double> positions;  // scene units, x y z interleaved
  std::vector<MeshFaceInput> faces;
  std::vector<MeshMaterialInput> materials;
};

// The Scene of `mesh`, named `name` in messages. INVALID_ARGUMENT naming what is wrong
// and where (the face index for a face with < 3 vertices, a vertex index out of range, an
// unknown material index or a vertex with a NaN/infinite coordinate; the material for a
// non-finite value or an opacity outside (0, 1]). The result is not yet validated: see
// ValidateScene.
absl::StatusOr<Scene> SceneFromMesh(const MeshInput& mesh, const std::string& name);

}  // namespace radflux
