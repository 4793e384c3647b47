#include "solver/hierarchical/cluster_link.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "solver/core/sampling.h"

namespace radflux {
namespace {

constexpr uint64_t kPickReceiverStream = 21;
constexpr uint64_t kPickSourceStream = 22;
constexpr uint64_t kReceiverPointStream = 23;
constexpr uint64_t kSourcePointStream = 24;

// The elements an end stands for: a cluster's faces, or the element itself.
std::span<const uint32_t> FacesOf(const LinkEnd& end) {
  return end.faces.empty() ? std::span<const uint32_t>(&end.id, 1) : end.faces;
}

// True when some face of `faces` and `e` are each in front of the other.
bool Exchanges(const ElementTree& tree, const Element& e, std::span<const uint32_t> faces) {
  for (uint32_t f : faces) {
    if (AnyCornerInFront(tree.nodes[f], e) && AnyCornerInFront(e, tree.nodes[f])) return true;
  }
  return false;
}

// Exposed area of `f` projected toward the point `to`, over pi (scene units^2).
double ProjectedArea(const Element& f, double exposure, const Vec3& to) {
  const Vec3 d = to - f.centroid;
  const double r = Length(d);
  if (!(r > 0)) return 0;
  return f.area * exposure * std::max(0.0, Dot(f.normal, d)) / (r * std::numbers::pi);
}

// Running sums of ProjectedArea toward `to` over `faces`.
std::vector<double> ProjectedAreaSums(const ElementTree& tree, std::span<const float> exposure,
                                      std::span<const uint32_t> faces, const Vec3& to) {
  std::vector<double> sums(faces.size());
  double sum = 0;
  for (size_t k = 0; k < faces.size(); ++k) {
    sum += ProjectedArea(tree.nodes[faces[k]], exposure[faces[k]], to);
    sums[k] = sum;
  }
  return sums;
}

// The face whose share of the running sums holds u in [0, 1).
uint32_t Pick(std::span<const uint32_t> faces, const std::vector<double>& sums, double u) {
  const auto it = std::upper_bound(sums.begin(), sums.end(), u * sums.back());
  return faces[std::min<size_t>(it - sums.begin(), faces.size() - 1)];
}

// Unblocked fraction of shadow rays between points of faces of p and q picked by projected
// exposed area toward the other's center; 1 when no picked pair faces each other.
double Visibility(const ElementTree& tree, std::span<const float> exposure, const LinkEnd& p,
                  const LinkEnd& q, const LinkSampling& sampling, const RayCaster& caster,
                  uint64_t& rays) {
  const std::vector<double> sums_p = ProjectedAreaSums(tree, exposure, FacesOf(p), q.center);
  const std::vector<double> sums_q = ProjectedAreaSums(tree, exposure, FacesOf(q), p.center);
  if (!(sums_p.back() > 0) || !(sums_q.back() > 0)) return 1;
  const uint64_t pair = sampling.seed ^ (uint64_t{p.id} << 32);
  const uint32_t pick_p = PatternSeed(pair, q.id, kPickReceiverStream);
  const uint32_t pick_q = PatternSeed(pair, q.id, kPickSourceStream);
  const uint32_t point_p = PatternSeed(pair, q.id, kReceiverPointStream);
  const uint32_t point_q = PatternSeed(pair, q.id, kSourcePointStream);
  const uint32_t s = static_cast<uint32_t>(sampling.samples);
  const MultiJitteredSets<2> drawn({point_p, point_q}, s);
  const std::span<const Point2> points_p = drawn[0], points_q = drawn[1];
  int facing = 0, seen = 0;
  for (uint32_t m = 0; m < s; ++m) {
    const Element& g = tree.nodes[Pick(FacesOf(p), sums_p, RandomFloat(m, pick_p))];
    const Element& f = tree.nodes[Pick(FacesOf(q), sums_q, RandomFloat(m, pick_q))];
    const Vec3 x = SampleElementPoint(g, points_p[m]);
    const Vec3 y = SampleElementPoint(f, points_q[m]);
    if (!(Dot(y - x, g.normal) > 0) || !(Dot(x - y, f.normal) > 0)) continue;
    ++facing;
    ++rays;
    const Vec3 origin = x + g.normal * sampling.ray_epsilon;
    const Vec3 target = y + f.normal * sampling.ray_epsilon;
    if (!caster.Occluded({origin, target - origin, 0, 1 - 1e-6})) ++seen;
  }
  return facing > 0 ? static_cast<double>(seen) / facing : 1.0;
}

}  // namespace

double ClusterFormFactorBound(const LinkEnd& p, const LinkEnd& q) {
  const double gap = Length(p.center - q.center) - p.radius - q.radius;
  if (!(gap > 0)) return 1;
  return std::min(1.0, q.area / (std::numbers::pi * gap * gap));
}

double PointTransfer(double k, const Vec3& x, const Vec3& n, const Vec3& center) {
  const Vec3 d = center - x;
  const double r2 = Dot(d, d);
  if (!(r2 > 0)) return 0;
  return k * std::max(0.0, Dot(n, d)) / (r2 * std::sqrt(r2));
}

bool EstimateClusterLink(const ElementTree& tree, std::span<const float> exposure, const LinkEnd& p,
                         const LinkEnd& q, const LinkSampling& sampling, const RayCaster& caster,
                         LinkEstimate& estimate, uint64_t& rays) {
  const bool p_cluster = IsCluster(p.id);
  if (!p_cluster && !Exchanges(tree, tree.nodes[p.id], FacesOf(q))) return false;
  if (!IsCluster(q.id) && !Exchanges(tree, tree.nodes[q.id], FacesOf(p))) return false;
  double f = 0;
  for (uint32_t s : FacesOf(q)) {
    const Element& source = tree.nodes[s];
    const double sending = exposure[s] * source.opacity;  // its exposed opaque share
    if (p_cluster) {
      f += ProjectedArea(source, sending, p.center);
    } else {
      const Element& e = tree.nodes[p.id];
      f += PointTransfer(ProjectedArea(source, sending, e.centroid), e.centroid, e.normal,
                         source.centroid);
    }
  }
  const double bound = ClusterFormFactorBound(p, q);
  if (f > 0) f *= Visibility(tree, exposure, p, q, sampling, caster, rays);
  estimate.ff = static_cast<float>(p_cluster ? f : std::min(f, bound));
  estimate.spread = static_cast<float>(bound);
  return true;
}

}  // namespace radflux
