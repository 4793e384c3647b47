#include "solver/mesh/patch_attributes.h"

namespace radflux {

PatchAttributes ComputePatchAttributes(const Scene& scene, const PatchMesh& mesh) {
  PatchAttributes out;
  out.area.reserve(mesh.size());
  out.reflectance.reserve(mesh.size());
  out.emission.reserve(mesh.size());
  for (const Patch& patch : mesh.patches) {
    const Material& m = scene.materials[scene.faces[patch.face].material];
    out.area.push_back(patch.area * m.opacity);
    out.reflectance.push_back(m.reflectance);
    out.emission.push_back(m.emission);
    out.grey = out.grey && IsGrey(m.reflectance) && IsGrey(m.emission);
  }
  return out;
}

}  // namespace radflux
