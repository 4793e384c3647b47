#include "solver/output/render.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "absl/strings/str_cat.h"
#include "solver/core/inverse_bilinear.h"
#include "solver/core/parallel.h"

namespace radflux {
namespace {

// Radiance (B/pi) seen along `ray`: black on a miss or a back-face hit.
Rgb TraceRadiance(const PatchMesh& mesh, const RayCaster& caster,
                  const std::vector<Rgb>& vertex_radiosity, const Ray& ray) {
  const Hit hit = caster.Intersect(ray);
  if (hit.patch == kNoPatch || hit.patch >= mesh.size()) return {};
  if (Dot(ray.direction, mesh.patches[hit.patch].normal) >= 0) return {};
  Rgb b = InterpolateAtHit(mesh, vertex_radiosity, hit);
  for (double& value : b) value /= std::numbers::pi;
  return b;
}

void RenderRow(const PatchMesh& mesh, const RayCaster& caster,
               const std::vector<Rgb>& vertex_radiosity, const PinholeProjection& projection, int n,
               int y, Image& image) {
  const double weight = 1.0 / (n * n);
  for (int x = 0; x < image.width; ++x) {
    Rgb sum{};
    for (int sy = 0; sy < n; ++sy) {
      for (int sx = 0; sx < n; ++sx) {
        const Ray ray = projection.RayThrough(x + (sx + 0.5) / n, y + (sy + 0.5) / n);
        const Rgb radiance = TraceRadiance(mesh, caster, vertex_radiosity, ray);
        for (int b = 0; b < kBands; ++b) sum[b] += radiance[b];
      }
    }
    float* pixel = image.Pixel(x, y);
    for (int b = 0; b < kBands; ++b) pixel[b] = static_cast<float>(sum[b] * weight);
  }
}

// Parameters (s, t) in [0, 1]^2 of `point` (in the plane of quad p): core/inverse_bilinear.h.
std::pair<double, double> InverseBilinear(const PatchMesh& mesh, uint32_t p, const Vec3& point) {
  return InverseBilinear(
      {mesh.Vertex(p, 0), mesh.Vertex(p, 1), mesh.Vertex(p, 2), mesh.Vertex(p, 3)},
      mesh.patches[p].normal, point);
}

// Whether quad p is a parallelogram (v0 - v1 + v2 - v3 = 0 within 1e-6 of its edges): its
// bilinear map is affine, and Embree's (u, v) are its parameters (s, t) on both triangles.
bool IsParallelogram(const PatchMesh& mesh, uint32_t p) {
  const Vec3 v0 = mesh.Vertex(p, 0);
  const Vec3 e = mesh.Vertex(p, 1) - v0, f = mesh.Vertex(p, 3) - v0;
  const Vec3 g = mesh.Vertex(p, 2) - mesh.Vertex(p, 1) - f;
  return Dot(g, g) <= 1e-12 * (Dot(e, e) + Dot(f, f));
}

}  // namespace

std::array<double, 4> PatchVertexWeights(const PatchMesh& mesh, uint32_t p, double u, double v) {
  const Patch& patch = mesh.patches[p];
  u = std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0);
  if (patch.IsTriangle()) {
    const double s = u + v > 1 ? 1 / (u + v) : 1;  // only rounding can push u+v past 1
    return {1 - (u + v) * s, u * s, v * s, 0};
  }
  if (IsParallelogram(mesh, p)) return {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
  const std::array<double, 4> in_triangle = u + v <= 1
                                                ? std::array<double, 4>{1 - u - v, u, 0, v}
                                                : std::array<double, 4>{0, 1 - v, u + v - 1, 1 - u};
  Vec3 point;
  for (int k = 0; k < 4; ++k) point += mesh.Vertex(p, k) * in_triangle[k];
  const auto [s, t] = InverseBilinear(mesh, p, point);
  return {(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t};
}

Rgb InterpolateAtHit(const PatchMesh& mesh, const std::vector<Rgb>& vertex_values, const Hit& hit) {
  const Patch& patch = mesh.patches[hit.patch];
  const std::array<double, 4> w = PatchVertexWeights(mesh, hit.patch, hit.u, hit.v);
  Rgb value{};
  for (int k = 0; k < 4; ++k) {
    if (w[k] == 0) continue;
    for (int b = 0; b < kBands; ++b) value[b] += w[k] * vertex_values[patch.v[k]][b];
  }
  return value;
}

absl::StatusOr<Image> RenderRadiance(const PatchMesh& mesh, const RayCaster& caster,
                                     const std::vector<Rgb>& vertex_radiosity, const Camera& camera,
                                     const RenderOptions& options) {
  if (absl::Status s = ValidateCamera(camera); !s.ok()) return s;
  if (vertex_radiosity.size() != mesh.positions.size()) {
    return absl::InvalidArgumentError(absl::StrCat("render: ", vertex_radiosity.size(),
                                                   " vertex values for ", mesh.positions.size(),
                                                   " vertices"));
  }
  if (options.samples_per_axis < 1 || options.samples_per_axis > 64) {
    return absl::InvalidArgumentError("render: samples_per_axis must be in [1, 64]");
  }
  const PinholeProjection projection(camera);
  Image image(camera.width, camera.height);
  ParallelFor(camera.height, 1, options.threads, [&](int64_t begin, int64_t end) {
    for (int64_t y = begin; y < end; ++y) {
      RenderRow(mesh, caster, vertex_radiosity, projection, options.samples_per_axis,
                static_cast<int>(y), image);
    }
  });
  return image;
}

}  // namespace radflux
