#include "solver/scene/mesh_scene.h"

#include <cmath>
#include <map>
#include <numbers>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

bool IsFiniteRgb(const Rgb& rgb) {
  for (double v : rgb)
    if (!std::isfinite(v)) return false;
  return true;
}

absl::Status CheckMaterial(const MeshMaterialInput& m, size_t k, const std::string& name) {
  const std::string material = absl::StrCat(name, ": material ", k, " '", m.name, "': ");
  const char* what = !IsFiniteRgb(m.reflectance)        ? "reflectance"
                     : !IsFiniteRgb(m.emitted_radiance) ? "emitted radiance"
                                                        : nullptr;
  if (what != nullptr) {
    return absl::InvalidArgumentError(absl::StrCat(material, what, " is NaN or infinite"));
  }
  if (!(m.opacity > 0 && m.opacity <= 1)) {
    return absl::InvalidArgumentError(
        absl::StrCat(material, "opacity ", m.opacity, " is outside (0, 1]"));
  }
  return absl::OkStatus();
}

absl::Status CheckFace(const MeshInput& mesh, size_t f, const std::string& name) {
  const MeshFaceInput& face = mesh.faces[f];
  const auto error = [&](const std::string& what) {
    return absl::InvalidArgumentError(absl::StrCat(name, ": face ", f, ": ", what));
  };
  if (face.vertices.size() < 3) {
    return error(absl::StrCat("has ", face.vertices.size(), " vertices; a face needs at least 3"));
  }
  const size_t vertex_count = mesh.positions.size() / 3;
  for (uint32_t v : face.vertices) {
    if (v >= vertex_count) {
      return error(absl::StrCat("vertex index ", v, " is out of range (the mesh has ", vertex_count,
                                " vertices)"));
    }
    for (int axis = 0; axis < 3; ++axis) {
      if (!std::isfinite(mesh.positions[3 * size_t{v} + axis])) {
        return error(absl::StrCat("vertex ", v, " has a NaN or infinite coordinate"));
      }
    }
  }
  if (face.material >= mesh.materials.size()) {
    return error(absl::StrCat("unknown material index ", face.material, " (the mesh has ",
                              mesh.materials.size(), " materials)"));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<Scene> SceneFromMesh(const MeshInput& mesh, const std::string& name) {
  if (mesh.positions.size() % 3 != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(name, ": ", mesh.positions.size(), " position values are not x y z triples"));
  }
  Scene scene;
  scene.source = name;
  for (size_t k = 0; k < mesh.materials.size(); ++k) {
    const MeshMaterialInput& m = mesh.materials[k];
    if (absl::Status s = CheckMaterial(m, k, name); !s.ok()) return s;
    Material material;
    material.name = m.name;
    material.reflectance = m.reflectance;
    material.opacity = m.opacity;
    for (int b = 0; b < kBands; ++b)
      material.emission[b] = std::numbers::pi * m.emitted_radiance[b];
    scene.materials.push_back(std::move(material));
  }
  for (size_t v = 0; v < mesh.positions.size(); v += 3) {
    scene.positions.push_back({mesh.positions[v], mesh.positions[v + 1], mesh.positions[v + 2]});
  }
  std::map<std::string, uint32_t> object_index, group_index;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (absl::Status s = CheckFace(mesh, f, name); !s.ok()) return s;
    const MeshFaceInput& input = mesh.faces[f];
    Face face;
    face.vertices = input.vertices;
    face.material = input.material;
    face.object = InternName(scene.objects, object_index, input.object);
    face.group = InternName(scene.groups, group_index, input.group);
    scene.faces.push_back(std::move(face));
  }
  return scene;
}

}  // namespace radflux
