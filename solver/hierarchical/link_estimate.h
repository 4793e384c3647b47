// The transport estimate of one hierarchical link p <- q between two elements (planar
// pieces of input faces): F_pq averaged over p, and how much F varies over p, which is what
// a link at p's level gets wrong for the points of p.
#pragma once

#include <cstdint>

#include "solver/mesh/adaptive_tree.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

struct LinkSampling {
  int samples = 4;         // points of p (two shadow rays each); more for near pairs
  uint64_t seed = 1;       // point patterns depend only on (seed, p) and (seed, p, q)
  double ray_epsilon = 0;  // shadow ray offsets along the normals, scene units
};

struct LinkEstimate {
  float ff = 0;      // F_pq with visibility, averaged over p
  float spread = 0;  // max - min of the point form factor F(x, q) over x in p (bound)
};

// True when some corner of `of` lies in front of the plane of `plane` (beyond a tolerance of
// 1e-9 times its size).
bool AnyCornerInFront(const Element& of, const Element& plane);

// Estimates F_pq from p's sample points: exact Lambert point-to-polygon F to the part of q in
// front of p (zero at points behind q's plane), averaged, times the fraction of the kernel
// cos cos / r^2 that is unblocked. Each point casts two shadow rays to points uniform on that
// front part: the "value" rays give that fraction (each weighted by its kernel, so a nearby
// unblocked part of q counts as much as it transports); the independent "decision" rays give
// the spread, so the choice to refine a link (which keeps it or replaces it) is independent
// of its value and the kept values stay unbiased. spread covers the samples and p's corners
// (unoccluded at corners), and is the largest unoccluded F when any decision ray is blocked
// (a shadow edge may cross p, or q may be hidden). ff and spread are times q's opacity (the
// share of light from p that meets q's opaque part; the shadow rays pass through partly
// transparent patches as the caster decides). Returns false when p and q cannot exchange
// light (no part of either in front of the other). `p_id`/`q_id` seed the patterns.
bool EstimateElementLink(const Element& p, const Element& q, uint32_t p_id, uint32_t q_id,
                         const LinkSampling& sampling, const RayCaster& caster,
                         LinkEstimate& estimate, uint64_t& rays);

}  // namespace radflux
