// The transport estimate of a hierarchical link p <- q when p or q is a cluster (Smits, Arvo
// and Greenberg 1994): a conservative form-factor bound that drives refinement, and a
// point-to-faces estimate with a few shadow rays for the links the bound lets stand. Faces
// are seen from afar (each as its area at its centroid), which the bound makes good enough:
// a link stays at a cluster only while A_q / (pi r^2) is small.
#pragma once

#include <cstdint>
#include <span>

#include "solver/hierarchical/cluster_tree.h"
#include "solver/hierarchical/link_estimate.h"
#include "solver/mesh/adaptive_tree.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

// One end of a link as the cluster estimates see it.
struct LinkEnd {
  uint32_t id = 0;                  // node id (element or kClusterBit | cluster)
  Vec3 center;                      // element centroid or cluster center
  double radius = 0;                // bounding sphere about `center`, scene units
  double area = 0;                  // total area, scene units^2
  std::span<const uint32_t> faces;  // a cluster's faces (root elements); empty for an element
};

// Bound on the form factor from any point of p to q, ignoring visibility and cosines:
// A_q / (pi r^2) with r the gap between the bounding spheres, clamped to 1 (1 when they touch).
double ClusterFormFactorBound(const LinkEnd& p, const LinkEnd& q);

// The form factor from a point x with normal n to a distant source at `center` whose exposed
// area seen from x, projected and divided by pi, is `k` (scene units^2): k cos / r^2.
double PointTransfer(double k, const Vec3& x, const Vec3& n, const Vec3& center);

// Estimates link p <- q (p or q a cluster; `exposure` per element, ExposedFraction). For an
// element receiver, ff is F_pq: the sum over q's faces of A_f e_f a_f cos cos / (pi r^2)
// between centroids (a_f the face's opacity: only its opaque part sends); for a cluster
// receiver, ff is k = sum over q's faces of A_f e_f a_f cos_f / pi toward
// p's center, which the gather turns into F per receiving face with PointTransfer. Both are
// times a visibility from `sampling.samples` shadow rays between points of faces of p and q
// picked by projected exposed area toward each other (1 when no picked pair faces). spread is
// ClusterFormFactorBound. Returns false when an element and a cluster cannot exchange light
// (no face of the cluster and the element each in front of the other).
bool EstimateClusterLink(const ElementTree& tree, std::span<const float> exposure, const LinkEnd& p,
                         const LinkEnd& q, const LinkSampling& sampling, const RayCaster& caster,
                         LinkEstimate& estimate, uint64_t& rays);

}  // namespace radflux
