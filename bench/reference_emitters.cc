#include "bench/reference_emitters.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/core/spherical_sampling.h"

namespace radflux {

double ClippedPolygonFormFactor(const Vec3* v, int count, const Vec3& x, const Vec3& n) {
  // Sutherland-Hodgman against n . (p - x) >= 0: at most count + 1 vertices.
  std::array<Vec3, 8> clipped;
  int m = 0;
  for (int i = 0; i < count; ++i) {
    const Vec3 &a = v[i], &b = v[(i + 1) % count];
    const double ha = Dot(n, a - x), hb = Dot(n, b - x);
    if (ha >= 0) clipped[m++] = a - x;
    if ((ha >= 0) != (hb >= 0)) clipped[m++] = a - x + (b - a) * (ha / (ha - hb));
  }
  if (m < 3) return 0;
  // Lambert: F = 1/(2 pi) sum over edges of the angle they subtend times n . (edge plane's
  // unit normal); the sign follows the winding, hence the absolute value.
  double sum = 0;
  for (int i = 0; i < m; ++i) {
    const Vec3 a = Normalize(clipped[i]), b = Normalize(clipped[(i + 1) % m]);
    const Vec3 c = Cross(a, b);
    const double s = Length(c);
    if (s <= 0) continue;
    sum += std::atan2(s, Dot(a, b)) * Dot(n, c) / s;
  }
  return std::min(1.0, std::abs(sum) / (2 * std::numbers::pi));
}

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
  std::array<Vec3, 4> corners;
  for (int i = 0; i < patch.VertexCount(); ++i) corners[i] = mesh_.positions[patch.v[i]];
  return luminance_[k] * ClippedPolygonFormFactor(corners.data(), patch.VertexCount(), x, n);
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
