// PairPatches: what the analytic pairs read of every patch, laid out once per mesh so that
// a pair costs no vertex-index chasing, square root or sampler set-up. Every value is the
// one the pair code would compute from the PatchMesh itself, bit for bit.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/mesh/patch_mesh.h"

namespace radflux {

// One patch as a receiver or target of analytic pairs.
struct PairPatch {
  // The patch's vertices in order; corner[3] == corner[2] for a triangle.
  std::array<Vec3, 4> corner;
  Vec3 centroid;            // as Patch::centroid
  Vec3 normal;              // as Patch::normal (unit, front side)
  double front_margin = 0;  // 1e-9 sqrt(area): a point further than this along the normal
                            // from the centroid is in front of the patch's plane
  uint32_t corners = 0;     // 3 or 4
};

class PairPatches {
 public:
  explicit PairPatches(const PatchMesh& mesh);
  const PairPatch& operator[](uint32_t p) const { return patch_[p]; }
  // Uniform-by-area points on patch p (PatchPointSampler(mesh, p)).
  const PatchPointSampler& Sampler(uint32_t p) const { return sampler_[p]; }

 private:
  std::vector<PairPatch> patch_;
  std::vector<PatchPointSampler> sampler_;
};

}  // namespace radflux
