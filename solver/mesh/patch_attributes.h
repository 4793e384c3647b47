// Per-patch material values looked up through the patch's source face.
#pragma once

#include <vector>

#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"

namespace radflux {

struct PatchAttributes {
  std::vector<double> area;       // scene units^2
  std::vector<Rgb> reflectance;   // rho per band
  std::vector<Rgb> emission;      // E, W/m^2 per band
  bool grey = true;               // every rho and E equal across bands: one band suffices

  size_t size() const { return area.size(); }
};

PatchAttributes ComputePatchAttributes(const Scene& scene, const PatchMesh& mesh);

}  // namespace radflux
