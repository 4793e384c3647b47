// The Gouraud picture's mean over each patch as a linear map of the welded vertex values, and
// a damped least-squares change of those values towards making every shown patch's mean its
// radiosity, so that the picture carries each patch's power, A_i B_i, instead of moving light
// to the next patch. A smoothing vertex fit moves it wherever B is curved: under the Cornell
// box's lamp, in the plane of the back wall's top edge, the wall's second row of patches read
// 1.7% dark and its edge row bright, and the picture's surface means (the eroded inside of
// each surface, against Cycles) were 0.1-0.7% dark with the solution's own means right.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/shading_mesh.h"

namespace radflux {

// Patch p's mean of its Gouraud interpolant, bilinear in the quad's own parameters (s, t) as
// the renderer interpolates (render.h) or linear on a triangle: sum over its n corners of
// weight[k] x value[welded[k]]. The weights sum to 1: 1/4 each on a parallelogram, 1/3 on a
// triangle, by area (the Jacobian) on any other planar quad.
struct PatchMeanWeights {
  int n = 0;
  std::array<uint32_t, 4> welded{};
  std::array<double, 4> weight{};
};
PatchMeanWeights GouraudMeanWeights(const PatchMesh& mesh, const ShadingMesh& shading, uint32_t p);

// Each T-junction vertex takes the interpolation along its edge; longer edges first, so a
// junction on an edge whose end is itself a junction sees that end's final value.
class TJunctionMap {
 public:
  TJunctionMap(const PatchMesh& mesh, const ShadingMesh& shading);
  void Apply(std::vector<Rgb>& values) const;
  // The transpose of Apply as a linear map: a junction's value goes back to its edge's ends.
  void ApplyTransposed(std::vector<Rgb>& values) const;

 private:
  struct Step {
    uint32_t vertex, a, b;
    double t;
  };
  std::vector<Step> steps_;  // in the order Apply takes them
};

// Every patch's Gouraud mean weights and the shading mesh's T-junctions, built once for a
// picture (the vertex fit's correction step and MatchPatchMeans both take them).
struct GouraudMeans {
  GouraudMeans(const PatchMesh& mesh, const ShadingMesh& shading);
  std::vector<PatchMeanWeights> patches;  // per patch: GouraudMeanWeights
  TJunctionMap junctions;
  // Per patch, the Gouraud mean of `values` (one per welded vertex).
  std::vector<Rgb> Means(const std::vector<Rgb>& values) const;
};

// Moves `values` (welded, junctions applied) by the change x that minimises
//   sum over shown patches of A_p (Gouraud mean_p - b_p)^2 + kDamping sum_v a_v x_v^2
// (a_v: the area vertex v carries in its patches' means), then clamps at zero and applies the
// junctions again: smooth deficits go (to 9%), rough ones that only noise makes stay smoothed
// (gouraud_means.cc). A field the values already carry (a linear one) is left as it is.
// Hidden patches (Patch::hidden) constrain nothing. `means` is GouraudMeans(mesh, shading).
void MatchPatchMeans(const PatchMesh& mesh, const GouraudMeans& means, const std::vector<Rgb>& b,
                     std::vector<Rgb>& values);

}  // namespace radflux
