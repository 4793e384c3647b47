#include "solver/hierarchical/link_estimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "solver/core/sampling.h"
#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

constexpr uint64_t kPointStream = 11;
constexpr uint64_t kDecisionStream = 12;
constexpr uint64_t kValueStream = 13;
// Near pairs take this many times the points: 4 is as accurate as 16 on the closed forms and
// the Cornell box's field error, with a third of the rays (bench/RESULTS.md, session 10).
constexpr int kNearFactor = 4;
constexpr double kCornerInset = 1e-3;  // corners are pulled this far toward the centroid

// A convex polygon (at most 5 vertices after one clip; room for the 8 that rounding can give
// a sliver along the plane) with its fan triangle areas.
struct FrontPolygon {
  std::array<Vec3, 8> v;
  size_t n = 0;
  std::array<double, 6> fan_area{};
  double area = 0;

  std::span<const Vec3> Points() const { return {v.data(), n}; }
  // Uniform by area for u in [0,1)^2.
  Vec3 Sample(Point2 u) const {
    double target = u.x * area;
    size_t t = 0;
    while (t + 3 < n && target >= fan_area[t]) target -= fan_area[t++];
    const double ux = std::clamp(target / fan_area[t], 0.0, 0x1.fffffffffffffp-1);
    const auto [b0, b1] = SampleUniformTriangle({ux, u.y});
    return v[0] * b0 + v[t + 1] * b1 + v[t + 2] * (1 - b0 - b1);
  }
};

FrontPolygon ClipInFront(const Element& q, const Element& p) {
  FrontPolygon f;
  const std::array<Vec3, 4> corners = q.corners;
  f.n = ClipPolygonToHalfSpace(std::span<const Vec3>(corners.data(), q.CornerCount()), p.centroid,
                               p.normal, f.v);
  for (size_t t = 0; t + 2 < f.n; ++t) {
    f.fan_area[t] = Length(Cross(f.v[t + 1] - f.v[0], f.v[t + 2] - f.v[0])) / 2;
    f.area += f.fan_area[t];
  }
  return f;
}

// Point form factor from x on p to the front part of q; zero when x is behind q's plane.
double PointFormFactor(const Vec3& x, const Element& p, const Element& q,
                       const FrontPolygon& front) {
  if (Dot(x - q.centroid, q.normal) <= 0) return 0;
  return UnclippedPointToPolygonFormFactor(x, p.normal, front.Points());
}

}  // namespace

bool AnyCornerInFront(const Element& of, const Element& plane) {
  const double scale = std::sqrt(plane.area);
  for (int k = 0; k < of.CornerCount(); ++k) {
    if (Dot(of.corners[k] - plane.centroid, plane.normal) > 1e-9 * scale) return true;
  }
  return false;
}

bool EstimateElementLink(const Element& p, const Element& q, uint32_t p_id, uint32_t q_id,
                         const LinkSampling& sampling, const RayCaster& caster,
                         LinkEstimate& estimate, uint64_t& rays) {
  if (p_id == q_id || !AnyCornerInFront(q, p) || !AnyCornerInFront(p, q)) return false;
  const FrontPolygon front = ClipInFront(q, p);
  if (front.n < 3 || !(front.area > 0)) return false;
  // Near pairs (within about one element size) have a near-singular kernel over p.
  const double size = std::sqrt(std::max(p.area, q.area));
  const bool near = Length(p.centroid - q.centroid) < 1.5 * size;
  const int s = sampling.samples * (near ? kNearFactor : 1);
  const uint32_t point_pattern = PatternSeed(sampling.seed, p_id, kPointStream);
  const uint64_t pair = sampling.seed ^ (uint64_t{p_id} << 32);
  const uint32_t decision_pattern = PatternSeed(pair, q_id, kDecisionStream);
  const uint32_t value_pattern = PatternSeed(pair, q_id, kValueStream);
  const MultiJitteredSets<3> drawn({point_pattern, decision_pattern, value_pattern},
                                   static_cast<size_t>(s));
  const std::span<const Point2> points = drawn[0], decision_targets = drawn[1],
                                value_targets = drawn[2];
  double unoccluded = 0, lo = 1, hi = 0, unoccluded_hi = 0;
  double kernel = 0, kernel_seen = 0;  // sum of cos cos / r^2 over value rays, and unblocked
  int visible = 0, blocked = 0;
  for (int m = 0; m < s; ++m) {
    const Vec3 x = SampleElementPoint(p, points[m]);
    const double f = PointFormFactor(x, p, q, front);
    lo = std::min(lo, f);
    unoccluded_hi = std::max(unoccluded_hi, f);
    if (f <= 0) continue;
    unoccluded += f;
    const Vec3 origin = x + p.normal * sampling.ray_epsilon;
    auto target = [&](std::span<const Point2> targets) {
      return front.Sample(targets[m]) + q.normal * sampling.ray_epsilon;
    };
    auto occluded = [&](const Vec3& y) {
      ++rays;
      return caster.Occluded({origin, y - origin, 0, 1 - 1e-6});
    };
    if (occluded(target(decision_targets))) {
      ++blocked;
    } else {
      ++visible;
      hi = std::max(hi, f);
    }
    const Vec3 y = target(value_targets);
    const Vec3 d = y - origin;
    const double r2 = Dot(d, d);
    const double k = std::max(0.0, Dot(d, p.normal)) * std::max(0.0, -Dot(d, q.normal)) / (r2 * r2);
    kernel += k;
    if (!occluded(y)) kernel_seen += k;
  }
  if (unoccluded_hi <= 0) return false;
  for (int k = 0; k < p.CornerCount(); ++k) {
    const Vec3 x = p.corners[k] + (p.centroid - p.corners[k]) * kCornerInset;
    const double f = PointFormFactor(x, p, q, front);
    lo = std::min(lo, f);
    hi = std::max(hi, f);
    unoccluded_hi = std::max(unoccluded_hi, f);
  }
  const double visibility = kernel > 0 ? kernel_seen / kernel : (visible > 0 ? 1.0 : 0.0);
  // Only q's opaque part (Element::opacity) sends and receives: light meets it, and it
  // meets light, with that probability.
  estimate.ff = static_cast<float>(unoccluded / s * visibility * q.opacity);
  estimate.spread = static_cast<float>((blocked > 0 ? unoccluded_hi : hi - lo) * q.opacity);
  return true;
}

}  // namespace radflux
