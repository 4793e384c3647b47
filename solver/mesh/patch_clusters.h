// PatchClusters: the unknowns of the radiosity system when they are not the mesh's patches.
// Each unknown is a cluster of one or more patches of one object and material (see face_grouping.h
// for how they are chosen) that receives and shoots as one: its row averages its members' rows by
// area, a ray that hits any member counts for it, and after the solve every member shows the
// cluster's B. An empty PatchClusters means "unknown u is patch u".
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/core/bands.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"

namespace radflux {

struct PatchClusters {
  std::vector<uint32_t> of_patch;  // the unknown of each mesh patch
  std::vector<uint32_t> first;     // members of unknown u: members[first[u], first[u + 1])
  std::vector<uint32_t> members;   // mesh patches, grouped by unknown
  std::vector<double> area;        // per unknown, the sum of its members' areas, scene units^2

  bool empty() const { return first.empty(); }
  // Number of unknowns (0 when empty: the caller uses the mesh's patch count).
  size_t size() const { return first.empty() ? 0 : first.size() - 1; }
  std::span<const uint32_t> Members(uint32_t u) const {
    return {members.data() + first[u], members.data() + first[u + 1]};
  }
};

// Clusters from the unknown of every patch (unknowns numbered 0..count-1, each with at
// least one patch); members are listed in patch order.
PatchClusters ClustersFromAssignment(const PatchMesh& mesh, std::vector<uint32_t> of_patch,
                                     uint32_t count);

// Per-unknown attributes: area the members' sum times their opacity, reflectance and emission of
// the members' material (grouping never mixes materials).
PatchAttributes ComputeClusterAttributes(const Scene& scene, const PatchMesh& mesh,
                                         const PatchClusters& clusters);

// One value per mesh patch: each patch takes its unknown's value.
std::vector<Rgb> PushDownToPatches(const PatchClusters& clusters, const std::vector<Rgb>& b);

// A point on a surface with its unit front normal.
struct SurfacePoint {
  Vec3 x;
  Vec3 n;
};

// Uniform-by-area points over an unknown's member patches: u.x picks a member in proportion
// to its area (and is rescaled within it, so stratification is kept), then the member's
// PatchPointSampler places the point. A one-patch unknown maps u exactly as PatchPointSampler.
class UnknownPointSampler {
 public:
  // The points of unknown u (`clusters` null or empty: patch u).
  UnknownPointSampler(const PatchMesh& mesh, const PatchClusters* clusters, uint32_t u);
  SurfacePoint operator()(Point2 u) const;
  // Which member (index among the members) operator() uses for u.x, and u.x rescaled within it.
  std::pair<size_t, double> Member(double ux) const;
  // The patch operator() places u's point on.
  uint32_t MemberPatch(double ux) const { return members_[Member(ux).first]; }

 private:
  const PatchMesh& mesh_;
  std::vector<uint32_t> members_;
  std::vector<PatchPointSampler> samplers_;
  std::vector<double> cdf_;  // cumulative area fractions, cdf_.back() == 1
};

}  // namespace radflux
