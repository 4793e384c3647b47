// Per-patch material values looked up through the patch's source face.
// B is the radiosity of a patch's opaque part (Material::opacity): the power it emits and
// reflects is opacity * area * B, and rays meet it with probability opacity, so the rows
// are reciprocal in these areas (area_i F_ij = area_j F_ji) and every sum of power over
// patches (energy balance, the symmetric form, the solvers' norms) weighs by them.
#pragma once

#include <vector>

#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"

namespace radflux {

struct PatchAttributes {
  std::vector<double> area;       // opaque area, opacity * geometric area, scene units^2
  std::vector<Rgb> reflectance;   // rho per band
  std::vector<Rgb> emission;      // E, W/m^2 per band
  bool grey = true;               // every rho and E equal across bands: one band suffices

  size_t size() const { return area.size(); }
};

PatchAttributes ComputePatchAttributes(const Scene& scene, const PatchMesh& mesh);

}  // namespace radflux
