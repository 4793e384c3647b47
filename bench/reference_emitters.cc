#include "bench/reference_emitters.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/core/spherical_sampling.h"

namespace radflux {
namespace {

// The least cosine an emitter's weight takes at either end (a polygon whose centroid is
// below a point's horizon may still light it with its upper part).
constexpr double kMinCosine = 0.05;

}  // namespace

ReferenceEmitters::ReferenceEmitters(const Scene& scene, const PatchMesh& mesh)
    : mesh_(mesh), index_(mesh.size(), -1) {
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Rgb& e = scene.materials[scene.faces[mesh.patches[p].face].material].emission;
    if (MaxComponent(e) <= 0) continue;
    index_[p] = static_cast<int32_t>(patches_.size());
    patches_.push_back(p);
    luminance_.push_back((e[0] + e[1] + e[2]) / 3);
  }
}

double ReferenceEmitters::Weight(size_t k, const Vec3& x, const Vec3& n) const {
  const Patch& patch = mesh_.patches[patches_[k]];
  const Vec3 v0 = mesh_.positions[patch.v[0]];
  if (Dot(patch.normal, x - v0) <= 0) return 0;  // x is behind the emitter: it sends nothing
  bool above = false;  // any corner above x's horizon: then some of it can light x
  for (int i = 0; i < patch.VertexCount(); ++i)
    above = above || Dot(n, mesh_.positions[patch.v[i]] - x) > 0;
  if (!above) return 0;
  // The form factor of the patch's centroid as a disc of its area seen head-on at r^2 +
  // A / pi (<= 1 however near), its cosines kept from falling below kMinCosine, so that the
  // weight is positive wherever the emitter can light x.
  const Vec3 d = patch.centroid - x;
  const double r2 = Dot(d, d), r = std::sqrt(r2);
  const double cx = std::max(kMinCosine, Dot(n, d) / r);
  const double cy = std::max(kMinCosine, -Dot(patch.normal, d) / r);
  return luminance_[k] * patch.area * cx * cy / (std::numbers::pi * r2 + patch.area);
}

double ReferenceEmitters::Weights(const Vec3& x, const Vec3& n, std::vector<double>& weights) const {
  weights.resize(patches_.size());
  double total = 0;
  for (size_t k = 0; k < patches_.size(); ++k) total += weights[k] = Weight(k, x, n);
  return total;
}

std::array<double, 2> ReferenceEmitters::SolidAngles(size_t k, const Vec3& x) const {
  const Patch& patch = mesh_.patches[patches_[k]];
  const Vec3 a = Normalize(mesh_.positions[patch.v[0]] - x);
  const Vec3 b = Normalize(mesh_.positions[patch.v[1]] - x);
  const Vec3 c = Normalize(mesh_.positions[patch.v[2]] - x);
  if (patch.IsTriangle()) return {SphericalTriangleArea(a, b, c), 0};
  const Vec3 d = Normalize(mesh_.positions[patch.v[3]] - x);
  return {SphericalTriangleArea(a, b, c), SphericalTriangleArea(a, c, d)};
}

ReferenceEmitters::Sample ReferenceEmitters::Draw(const Vec3& x, const std::vector<double>& weights,
                                                  double total, double u_pick, Point2 u) const {
  // The emitter, by inverting the weights' running sum; what is left of u_pick picks the
  // triangle of a quad in proportion to its solid angle.
  double below = 0, target = u_pick * total;
  size_t k = 0;
  while (k + 1 < weights.size() && below + weights[k] <= target) below += weights[k++];
  if (weights[k] <= 0) return {};
  const double rest = std::clamp((target - below) / weights[k], 0.0, 1.0);
  const Patch& patch = mesh_.patches[patches_[k]];
  const auto omega = SolidAngles(k, x);
  const double sum = omega[0] + omega[1];
  if (!(sum > 0)) return {};
  const bool second = rest * sum >= omega[0];
  const std::array<Vec3, 3> tri{mesh_.positions[patch.v[0]],
                                mesh_.positions[patch.v[second ? 2 : 1]],
                                mesh_.positions[patch.v[second ? 3 : 2]]};
  double pdf = 0;
  const Vec3 w = SampleSphericalTriangle(tri, x, u, &pdf);
  const double facing = Dot(w, patch.normal);
  if (!(pdf > 0) || !(facing < 0)) return {};
  const double distance = Dot(tri[0] - x, patch.normal) / facing;
  return {patches_[k], w, distance, weights[k] / total * omega[second ? 1 : 0] / sum * pdf};
}

double ReferenceEmitters::Pdf(uint32_t patch, const Vec3& x, const Vec3& n, double total) const {
  const int32_t k = index_[patch];
  if (k < 0 || !(total > 0)) return 0;
  const auto omega = SolidAngles(static_cast<size_t>(k), x);
  const double sum = omega[0] + omega[1];
  return sum > 0 ? Weight(static_cast<size_t>(k), x, n) / total / sum : 0;
}

}  // namespace radflux
