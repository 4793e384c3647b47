#include "solver/output/render.h"

#include <algorithm>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "solver/core/parallel.h"
#include "solver/output/vertex_radiosity.h"
#include "solver/raytrace/embree_ray_caster.h"

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

}  // namespace

std::array<double, 4> PatchVertexWeights(const Patch& patch, double u, double v) {
  u = std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0);
  if (patch.IsTriangle()) {
    const double s = u + v > 1 ? 1 / (u + v) : 1;  // only rounding can push u+v past 1
    return {1 - (u + v) * s, u * s, v * s, 0};
  }
  if (u + v <= 1) return {1 - u - v, u, 0, v};  // triangle (v0, v1, v3)
  return {0, 1 - v, u + v - 1, 1 - u};          // triangle (v2, v3, v1) with u = 1-u', v = 1-v'
}

Rgb InterpolateAtHit(const PatchMesh& mesh, const std::vector<Rgb>& vertex_values, const Hit& hit) {
  const Patch& patch = mesh.patches[hit.patch];
  const std::array<double, 4> w = PatchVertexWeights(patch, hit.u, hit.v);
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

absl::StatusOr<Image> RenderPatchRadiosity(const PatchMesh& mesh,
                                           const std::vector<Rgb>& patch_radiosity,
                                           const Camera& camera, const RenderOptions& options) {
  auto vertex_radiosity = VertexRadiosity(mesh, patch_radiosity);
  if (!vertex_radiosity.ok()) return vertex_radiosity.status();
  auto caster = EmbreeRayCaster::Create(mesh);
  if (!caster.ok()) return caster.status();
  return RenderRadiance(mesh, **caster, *vertex_radiosity, camera, options);
}

}  // namespace radflux
