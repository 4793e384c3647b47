// What the emitters' light does to each patch, for face grouping (face_grouping.h): a group
// shares one B, so a patch the lamps light must not share an unknown with one they do not
// (a lamp housing's inside, 2 cm from its tube, with its outside and the cavity between its
// two shells: grouped together, the ceiling 2 cm above the outside gathered the inside's
// light, +95% in RenderPark's classroom), and a patch the lamps make a light source of its
// own (that inside) must be an unknown of its own, so that the rows light-sample it as a
// bright reflector (bright_reflectors.h) instead of meeting it by chance with cosine rays.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/mesh/face_grouping.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/raytrace/ray_caster.h"
#include "solver/scene/scene.h"

namespace radflux {

// Light samples per patch for the probe (light_sampling.h's stratified points, one shadow
// ray each; a patch near an emitter against its size takes up to 16 times as many).
inline constexpr int kLitProbePoints = 1;

// Per patch of `mesh` (of `scene`, traced by `caster`), by kLitProbePoints light samples. A
// patch no emitter can light is kUnlit whatever the samples (no unoccluded segment exists);
// one lit over a small part of it can read kUnlit too. Seeded per patch from a fixed seed,
// so every caller that meshes the scene alike gets the same answer, on any number of threads.
std::vector<DirectLight> ProbeDirectLight(const Scene& scene, const PatchMesh& mesh,
                                          const RayCaster& caster);

}  // namespace radflux
