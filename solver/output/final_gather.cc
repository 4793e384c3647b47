#include "solver/output/final_gather.h"

#include <algorithm>
#include <numbers>
#include <span>

#include "absl/strings/str_cat.h"
#include "solver/core/parallel.h"
#include "solver/core/sampling.h"
#include "solver/formfactor/light_sampling.h"
#include "solver/output/gather_lights.h"
#include "solver/output/render.h"
#include "solver/output/vertex_radiosity.h"

namespace radflux {
namespace {

// Pattern streams of a pixel's samples, apart from each other and from the light sampler's.
constexpr uint64_t kPixelStream = 31;
constexpr uint64_t kLightStream = 32;
constexpr uint64_t kGatherStream = 33;

// The row context light sampling needs for `lights` (every light patch an emitter).
RowContext LightContext(const GatherLights& lights, const RayCaster& caster, double ray_epsilon) {
  RowContext context;
  context.mesh = &lights.mesh;
  context.caster = &caster;
  context.ray_epsilon = ray_epsilon;
  context.needs_row.assign(lights.mesh.size(), 0);
  context.emitter.assign(lights.mesh.size(), 1);
  for (const Rgb& e : lights.emission) context.emission.push_back(e[0] + e[1] + e[2]);
  return context;
}

// Everything the rows of one gather read (not copyable: sampler_ points into light_context_).
class GatherScene {
 public:
  GatherScene(const PatchMesh& mesh, const RayCaster& caster, const PatchAttributes& attributes,
              std::vector<Rgb> reflected_at_vertex, const Camera& camera)
      : mesh_(mesh),
        caster_(caster),
        attributes_(attributes),
        reflected_at_vertex_(std::move(reflected_at_vertex)),
        lights_(MakeGatherLights(mesh, attributes)),
        light_context_(LightContext(lights_, caster, RayEpsilonFor(mesh))),
        sampler_(light_context_),
        projection_(camera) {}
  GatherScene(const GatherScene&) = delete;
  GatherScene& operator=(const GatherScene&) = delete;

  // Row y of the image, N = rays paths per pixel.
  void Row(int y, int rays, uint64_t seed, Image& image) const;

 private:
  // One path of a pixel: the patch it sees, and its light sample's and gather ray's index
  // among the row's (-1: none).
  struct Path {
    uint32_t patch = kNoPatch;
    int64_t light = -1, gather = -1;
  };
  // The row's light and gather rays, and the light samples' estimates.
  struct Secondary {
    std::vector<StreamRay> light_rays, gather_rays;
    std::vector<LightSampler::PendingSample> pending;
  };
  // Casts the row's primary rays, one per path, into `primary`.
  void CastPrimary(int y, int rays, uint64_t seed, int width,
                   std::vector<StreamRay>& primary) const;
  // Sets up each path that sees a patch: its light sample and gather ray, into `secondary`.
  void StartPaths(int y, int rays, uint64_t seed, std::span<const StreamRay> primary,
                  std::vector<Path>& paths, Secondary& secondary) const;
  // The radiance path `path` estimates, given its traced light and gather rays.
  Rgb PathRadiance(const Path& path, std::span<const StreamRay> light_rays,
                   std::span<const LightSampler::PendingSample> pending,
                   std::span<const StreamRay> gather_rays) const;

  const PatchMesh& mesh_;
  const RayCaster& caster_;
  const PatchAttributes& attributes_;
  std::vector<Rgb> reflected_at_vertex_;  // R = B - E, W/m^2 per band
  GatherLights lights_;
  RowContext light_context_;  // of lights_.mesh
  LightSampler sampler_;
  PinholeProjection projection_;
};

void GatherScene::CastPrimary(int y, int rays, uint64_t seed, int width,
                              std::vector<StreamRay>& primary) const {
  std::vector<Point2> in_pixel(static_cast<size_t>(rays));
  primary.assign(static_cast<size_t>(width) * rays, StreamRay{});
  for (int x = 0; x < width; ++x) {
    const uint64_t pixel = static_cast<uint64_t>(y) * width + x;
    MultiJitteredSamples(PatternSeed(seed, pixel, kPixelStream), in_pixel);
    for (int k = 0; k < rays; ++k) {
      const Ray ray = projection_.RayThrough(x + in_pixel[k].x, y + in_pixel[k].y);
      StreamRay& r = primary[static_cast<size_t>(x) * rays + k];
      r.SetOrigin(ray.origin);
      r.SetDirection(ray.direction);
    }
  }
  caster_.IntersectStream(primary);
}

Rgb GatherScene::PathRadiance(const Path& path, std::span<const StreamRay> light_rays,
                              std::span<const LightSampler::PendingSample> pending,
                              std::span<const StreamRay> gather_rays) const {
  Rgb irradiance{};  // H_direct + H_indirect at the path's point, W/m^2 per band
  if (path.light >= 0 && !light_rays[path.light].Occluded()) {
    const LightSampler::PendingSample& sample = pending[path.light];
    const Rgb& e = lights_.emission[sample.emitter];
    for (int b = 0; b < kBands; ++b) irradiance[b] += e[b] * sample.form_factor;
  }
  const StreamRay& g = gather_rays[path.gather];
  if (const uint32_t q = g.FrontPatch(); q != kNoPatch && q < mesh_.size()) {
    Hit hit;
    hit.patch = q;
    hit.u = g.u;
    hit.v = g.v;
    const Rgb r = InterpolateAtHit(mesh_, reflected_at_vertex_, hit);
    for (int b = 0; b < kBands; ++b) irradiance[b] += std::max(0.0, r[b]);
  }
  const Rgb& rho = attributes_.reflectance[path.patch];
  const Rgb& e = attributes_.emission[path.patch];
  Rgb radiance;
  for (int b = 0; b < kBands; ++b) {
    radiance[b] = (e[b] + rho[b] * irradiance[b]) * std::numbers::inv_pi;
  }
  return radiance;
}

void GatherScene::StartPaths(int y, int rays, uint64_t seed, std::span<const StreamRay> primary,
                             std::vector<Path>& paths, Secondary& secondary) const {
  const int width = static_cast<int>(primary.size()) / rays;
  std::vector<Point2> light_points(static_cast<size_t>(rays)), gather_points(light_points);
  for (int x = 0; x < width; ++x) {
    const uint64_t pixel = static_cast<uint64_t>(y) * width + x;
    MultiJitteredSamples(PatternSeed(seed, pixel, kLightStream), light_points);
    MultiJitteredSamples(PatternSeed(seed, pixel, kGatherStream), gather_points);
    for (int k = 0; k < rays; ++k) {
      const size_t at = static_cast<size_t>(x) * rays + k;
      const StreamRay& r = primary[at];
      const uint32_t p = r.FrontPatch();
      if (p == kNoPatch || p >= mesh_.size()) continue;
      const Patch& patch = mesh_.patches[p];
      const Vec3 origin{r.org_x, r.org_y, r.org_z}, direction{r.dir_x, r.dir_y, r.dir_z};
      Vec3 point = origin + direction * static_cast<double>(r.t_far);
      point = point - patch.normal * Dot(point - mesh_.Vertex(p, 0), patch.normal);  // on p
      Path& path = paths[at];
      path.patch = p;
      const size_t before = secondary.light_rays.size();
      sampler_.SamplePoint(point, patch.normal, lights_.of_patch[p], seed, pixel,
                           static_cast<uint32_t>(k),
                           std::span<const Point2>(light_points).subspan(k, 1),
                           secondary.light_rays, secondary.pending);
      if (secondary.light_rays.size() > before) path.light = static_cast<int64_t>(before);
      StreamRay g;
      g.SetOrigin(point + patch.normal * light_context_.ray_epsilon);
      g.SetDirection(
          Frame::FromNormal(patch.normal).ToWorld(SampleCosineHemisphere(gather_points[k])));
      path.gather = static_cast<int64_t>(secondary.gather_rays.size());
      secondary.gather_rays.push_back(g);
    }
  }
}

void GatherScene::Row(int y, int rays, uint64_t seed, Image& image) const {
  std::vector<StreamRay> primary;
  CastPrimary(y, rays, seed, image.width, primary);
  std::vector<Path> paths(primary.size());
  Secondary secondary;
  StartPaths(y, rays, seed, primary, paths, secondary);
  caster_.OccludedStream(secondary.light_rays);
  caster_.IntersectStream(secondary.gather_rays);
  for (int x = 0; x < image.width; ++x) {
    Rgb sum{};
    for (int k = 0; k < rays; ++k) {
      const Path& path = paths[static_cast<size_t>(x) * rays + k];
      if (path.patch == kNoPatch) continue;
      const Rgb radiance =
          PathRadiance(path, secondary.light_rays, secondary.pending, secondary.gather_rays);
      for (int b = 0; b < kBands; ++b) sum[b] += radiance[b];
    }
    float* out = image.Pixel(x, y);
    for (int b = 0; b < kBands; ++b) out[b] = static_cast<float>(sum[b] / rays);
  }
}

}  // namespace

absl::StatusOr<Image> RenderFinalGather(const PatchMesh& mesh, const ShadingMesh& shading,
                                        const RayCaster& caster, const PatchAttributes& attributes,
                                        const std::vector<Rgb>& patch_radiosity,
                                        const Camera& camera, const GatherOptions& options) {
  if (absl::Status s = ValidateCamera(camera); !s.ok()) return s;
  if (patch_radiosity.size() != mesh.size() || attributes.size() != mesh.size()) {
    return absl::InvalidArgumentError(absl::StrCat("final gather: ", patch_radiosity.size(),
                                                   " radiosities and ", attributes.size(),
                                                   " attributes for ", mesh.size(), " patches"));
  }
  if (options.rays < 1 || options.rays > 4096) {
    return absl::InvalidArgumentError(
        absl::StrCat("final gather: --gather ", options.rays, " must be in [1, 4096]"));
  }
  std::vector<Rgb> reflected(mesh.size());
  for (size_t p = 0; p < mesh.size(); ++p) {
    for (int b = 0; b < kBands; ++b) {
      reflected[p][b] = patch_radiosity[p][b] - attributes.emission[p][b];
    }
  }
  absl::StatusOr<std::vector<Rgb>> at_vertex = VertexRadiosity(mesh, shading, reflected);
  if (!at_vertex.ok()) return at_vertex.status();
  const GatherScene scene(mesh, caster, attributes, *std::move(at_vertex), camera);
  Image image(camera.width, camera.height);
  ParallelFor(camera.height, 1, options.threads, [&](int64_t begin, int64_t end) {
    for (int64_t y = begin; y < end; ++y) {
      scene.Row(static_cast<int>(y), options.rays, options.seed, image);
    }
  });
  return image;
}

}  // namespace radflux
