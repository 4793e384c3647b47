#include "solver/output/final_gather.h"

#include <algorithm>
#include <array>
#include <numbers>
#include <span>

#include "absl/strings/str_cat.h"
#include "solver/core/parallel.h"
#include "solver/core/sampling.h"
#include "solver/formfactor/light_sampling.h"
#include "solver/output/gather_lights.h"
#include "solver/output/indirect_regather.h"
#include "solver/output/render.h"
#include "solver/output/vertex_radiosity.h"

namespace radflux {
namespace {

// Pattern streams of a pixel's samples, apart from each other and from the light sampler's.
constexpr uint64_t kPixelStream = 31;
constexpr uint64_t kLightStream = 32;
constexpr uint64_t kGatherStream = 33;
// Visible points per pixel: at least this many (or N), one per this many gather rays above.
constexpr int kMinPointsPerPixel = 16;
constexpr int kGatherRaysPerPoint = 8;
// The sample counts of a pixel of N gather rays: P = min(N, max(16, N / 8)) visible points
// (one primary ray each: at least 16 keep the pixel's footprint finely sampled), one light
// sample per point (point j takes sample j of the pixel's multi-jittered light pattern), and
// the N gather rays, of which point j takes rays j, j + P, ... (strided through the pixel's
// multi-jittered gather pattern, so that a point's rays are spread, not in one row of it). The
// indirect light is the noisy part where the emitters are hidden, and a gather ray costs far less
// than a primary ray and a light sample's set-up: at N = 128 on the Cornell box, 16 points with one
// light sample each leave 93.4% of the 4x4 blocks within 3% of Cycles at 2.4 CPU-s, where 64 points
// with two took 4.2 CPU-s for 94.8%.
struct PixelSamples {
  int points = 0, gather = 0;
};
PixelSamples SamplesPerPixel(int rays) {
  return {std::min(rays, std::max(kMinPointsPerPixel, rays / kGatherRaysPerPoint)), rays};
}

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
  // With `gathered`, `at_vertex` is R = B - E, met by the gather rays; otherwise it is the
  // indirect radiosity I (indirect_regather.h) at the visible point itself. Either way the
  // lights shine with their E: what an emitter reflects is in R and in I.
  GatherScene(const PatchMesh& mesh, const RayCaster& caster, const PatchAttributes& attributes,
              std::vector<Rgb> at_vertex, bool gathered, const Camera& camera)
      : mesh_(mesh),
        caster_(caster),
        attributes_(attributes),
        at_vertex_(std::move(at_vertex)),
        gathered_(gathered),
        lights_(MakeGatherLights(mesh, attributes)),
        light_context_(LightContext(lights_, caster, RayEpsilonFor(mesh))),
        sampler_(light_context_),
        projection_(camera) {}
  GatherScene(const GatherScene&) = delete;
  GatherScene& operator=(const GatherScene&) = delete;

  // Row y of the image, with `samples` per pixel.
  void Row(int y, const PixelSamples& samples, uint64_t seed, Image& image) const;

 private:
  // One visible point of a pixel: the patch it sees, and the ranges of its light sample
  // and gather rays among the row's (a light sample whose emitter cannot be seen from the
  // point casts no ray and adds nothing).
  struct Point {
    uint32_t patch = kNoPatch;
    float u = 0, v = 0;  // where the primary ray met the patch (Embree's coordinates)
    size_t light_begin = 0, light_end = 0, gather_begin = 0, gather_end = 0;
  };
  // The row's light and gather rays, and the light samples' estimates.
  struct Secondary {
    std::vector<StreamRay> light_rays, gather_rays;
    std::vector<LightSampler::PendingSample> pending;
  };
  // Casts the row's primary rays, one per visible point, into `primary`.
  void CastPrimary(int y, const PixelSamples& samples, uint64_t seed, int width,
                   std::vector<StreamRay>& primary) const;
  // Sets up the light sample and the gather rays of each point that sees a patch, into
  // `secondary`.
  void StartPaths(int y, const PixelSamples& samples, uint64_t seed,
                  std::span<const StreamRay> primary, std::vector<Point>& points,
                  Secondary& secondary) const;
  // The radiance that `point` estimates from its traced light and gather rays.
  Rgb PointRadiance(const Point& point, const Secondary& secondary) const;

  const PatchMesh& mesh_;
  const RayCaster& caster_;
  const PatchAttributes& attributes_;
  std::vector<Rgb> at_vertex_;  // R = B - E, or I (see the constructor), W/m^2 per band
  bool gathered_;
  GatherLights lights_;
  RowContext light_context_;  // of lights_.mesh
  LightSampler sampler_;
  PinholeProjection projection_;
};

void GatherScene::CastPrimary(int y, const PixelSamples& samples, uint64_t seed, int width,
                              std::vector<StreamRay>& primary) const {
  const int points = samples.points;
  std::vector<Point2> in_pixel(static_cast<size_t>(points));
  primary.assign(static_cast<size_t>(width) * points, StreamRay{});
  for (int x = 0; x < width; ++x) {
    const uint64_t pixel = static_cast<uint64_t>(y) * width + x;
    MultiJitteredSamples(PatternSeed(seed, pixel, kPixelStream), in_pixel);
    for (int k = 0; k < points; ++k) {
      const Ray ray = projection_.RayThrough(x + in_pixel[k].x, y + in_pixel[k].y);
      StreamRay& r = primary[static_cast<size_t>(x) * points + k];
      r.SetOrigin(ray.origin);
      r.SetDirection(ray.direction);
    }
  }
  caster_.IntersectStream(primary);
}

Rgb GatherScene::PointRadiance(const Point& point, const Secondary& secondary) const {
  Rgb direct{};  // H_direct's sample, W/m^2 per band
  for (size_t i = point.light_begin; i < point.light_end; ++i) {
    if (secondary.light_rays[i].Occluded()) continue;
    const LightSampler::PendingSample& sample = secondary.pending[i];
    const Rgb& e = lights_.emission[sample.emitter];
    for (int b = 0; b < kBands; ++b) direct[b] += e[b] * sample.form_factor;
  }
  // H_indirect's samples summed
  const Rgb indirect =
      SumMetReflected(mesh_, at_vertex_,
                      std::span<const StreamRay>(secondary.gather_rays)
                          .subspan(point.gather_begin, point.gather_end - point.gather_begin));
  const Rgb& rho = attributes_.reflectance[point.patch];
  const Rgb& e = attributes_.emission[point.patch];
  Rgb radiance;
  if (gathered_) {
    const double gathers = static_cast<double>(point.gather_end - point.gather_begin);
    for (int b = 0; b < kBands; ++b) {
      radiance[b] = (e[b] + rho[b] * (direct[b] + indirect[b] / gathers)) * std::numbers::inv_pi;
    }
    return radiance;
  }
  Hit hit;
  hit.patch = point.patch;
  hit.u = point.u;
  hit.v = point.v;
  const Rgb at_point = InterpolateAtHit(mesh_, at_vertex_, hit);
  for (int b = 0; b < kBands; ++b) {
    radiance[b] = (e[b] + std::max(0.0, at_point[b]) + rho[b] * direct[b]) * std::numbers::inv_pi;
  }
  return radiance;
}

void GatherScene::StartPaths(int y, const PixelSamples& samples, uint64_t seed,
                             std::span<const StreamRay> primary, std::vector<Point>& points,
                             Secondary& secondary) const {
  const int per_pixel = samples.points;
  const int width = static_cast<int>(primary.size()) / per_pixel;
  std::vector<Point2> light_points(static_cast<size_t>(per_pixel));
  std::vector<Point2> gather_points(static_cast<size_t>(samples.gather));
  for (int x = 0; x < width; ++x) {
    const uint64_t pixel = static_cast<uint64_t>(y) * width + x;
    MultiJitteredSamples(PatternSeed(seed, pixel, kLightStream), light_points);
    MultiJitteredSamples(PatternSeed(seed, pixel, kGatherStream), gather_points);
    for (int j = 0; j < per_pixel; ++j) {
      const size_t at = static_cast<size_t>(x) * per_pixel + j;
      const StreamRay& r = primary[at];
      const uint32_t p = r.FrontPatch();
      if (p == kNoPatch || p >= mesh_.size()) continue;
      const Patch& patch = mesh_.patches[p];
      const Vec3 origin{r.org_x, r.org_y, r.org_z}, direction{r.dir_x, r.dir_y, r.dir_z};
      Vec3 x_on_p = origin + direction * static_cast<double>(r.t_far);
      x_on_p = x_on_p - patch.normal * Dot(x_on_p - mesh_.Vertex(p, 0), patch.normal);
      Point& point = points[at];
      point.patch = p;
      point.u = r.u;
      point.v = r.v;
      point.light_begin = secondary.light_rays.size();
      sampler_.SamplePoint(x_on_p, patch.normal, lights_.of_patch[p], seed, pixel,
                           static_cast<uint32_t>(j),
                           std::span<const Point2>(light_points).subspan(static_cast<size_t>(j), 1),
                           secondary.light_rays, secondary.pending);
      point.light_end = secondary.light_rays.size();
      point.gather_begin = secondary.gather_rays.size();
      const Frame frame = Frame::FromNormal(patch.normal);
      for (int k = j; k < samples.gather; k += per_pixel) {
        StreamRay g;
        g.SetOrigin(x_on_p + patch.normal * light_context_.ray_epsilon);
        g.SetDirection(frame.ToWorld(SampleCosineHemisphere(gather_points[k])));
        secondary.gather_rays.push_back(g);
      }
      point.gather_end = secondary.gather_rays.size();
    }
  }
}

void GatherScene::Row(int y, const PixelSamples& samples, uint64_t seed, Image& image) const {
  // Per-thread scratch, reused row to row (fresh vectors of this size cost page faults).
  thread_local std::vector<StreamRay> primary;
  thread_local std::vector<Point> points;
  thread_local Secondary secondary;
  CastPrimary(y, samples, seed, image.width, primary);
  points.assign(primary.size(), Point{});
  secondary.light_rays.clear();
  secondary.gather_rays.clear();
  secondary.pending.clear();
  StartPaths(y, samples, seed, primary, points, secondary);
  caster_.OccludedStream(secondary.light_rays);
  caster_.IntersectStream(secondary.gather_rays);
  const int per_pixel = samples.points;
  for (int x = 0; x < image.width; ++x) {
    Rgb sum{};
    for (int j = 0; j < per_pixel; ++j) {
      const Point& point = points[static_cast<size_t>(x) * per_pixel + j];
      if (point.patch == kNoPatch) continue;
      const Rgb radiance = PointRadiance(point, secondary);
      for (int b = 0; b < kBands; ++b) sum[b] += radiance[b];
    }
    float* out = image.Pixel(x, y);
    for (int b = 0; b < kBands; ++b) out[b] = static_cast<float>(sum[b] / per_pixel);
  }
}

}  // namespace

namespace {

// The checks both pictures make on their inputs: `what` names the picture and its count,
// `count` (rays or points per pixel) must be in [1, 4096].
absl::Status CheckInputs(const PatchMesh& mesh, const PatchAttributes& attributes,
                         const std::vector<Rgb>& patch_radiosity, const Camera& camera, int count,
                         const char* what) {
  if (absl::Status s = ValidateCamera(camera); !s.ok()) return s;
  if (patch_radiosity.size() != mesh.size() || attributes.size() != mesh.size()) {
    return absl::InvalidArgumentError(absl::StrCat(what, ": ", patch_radiosity.size(),
                                                   " radiosities and ", attributes.size(),
                                                   " attributes for ", mesh.size(), " patches"));
  }
  if (count < 1 || count > 4096) {
    return absl::InvalidArgumentError(absl::StrCat(what, " ", count, " must be in [1, 4096]"));
  }
  return absl::OkStatus();
}

Image RenderScene(const GatherScene& scene, const Camera& camera, const PixelSamples& samples,
                  const GatherOptions& options) {
  Image image(camera.width, camera.height);
  ParallelFor(camera.height, 1, options.threads, [&](int64_t begin, int64_t end) {
    for (int64_t y = begin; y < end; ++y) {
      scene.Row(static_cast<int>(y), samples, options.seed, image);
    }
  });
  return image;
}

}  // namespace

absl::StatusOr<Image> RenderFinalGather(const PatchMesh& mesh, const ShadingMesh& shading,
                                        const RayCaster& caster, const PatchAttributes& attributes,
                                        const std::vector<Rgb>& patch_radiosity,
                                        const Camera& camera, const GatherOptions& options) {
  if (absl::Status s = CheckInputs(mesh, attributes, patch_radiosity, camera, options.rays,
                                   "final gather: --gather");
      !s.ok()) {
    return s;
  }
  absl::StatusOr<VertexFit> fit = VertexFit::Build(mesh, shading);
  if (!fit.ok()) return fit.status();
  absl::StatusOr<std::vector<Rgb>> at_vertex =
      ReflectedAtVertices(mesh, *fit, attributes, patch_radiosity);
  if (!at_vertex.ok()) return at_vertex.status();
  const GatherScene scene(mesh, caster, attributes, *std::move(at_vertex), true, camera);
  return RenderScene(scene, camera, SamplesPerPixel(options.rays), options);
}

absl::StatusOr<Image> RenderDirectPerPixel(const PatchMesh& mesh, const ShadingMesh& shading,
                                           const RayCaster& caster,
                                           const PatchAttributes& attributes,
                                           const std::vector<Rgb>& patch_radiosity,
                                           const std::vector<Rgb>& patch_indirect,
                                           const Camera& camera, const GatherOptions& options) {
  if (absl::Status s = CheckInputs(mesh, attributes, patch_radiosity, camera, options.rays,
                                   "direct light per pixel: --pixel-samples");
      !s.ok()) {
    return s;
  }
  if (patch_indirect.size() != mesh.size()) {
    return absl::InvalidArgumentError(
        absl::StrCat("direct light per pixel: ", patch_indirect.size(), " indirect values for ",
                     mesh.size(), " patches"));
  }
  absl::StatusOr<VertexFit> fit = VertexFit::Build(mesh, shading);
  if (!fit.ok()) return fit.status();
  absl::StatusOr<std::vector<Rgb>> indirect =
      RegatherShownIndirect(mesh, *fit, caster, attributes, patch_radiosity, patch_indirect, camera,
                            options.seed, options.threads);
  if (!indirect.ok()) return indirect.status();
  absl::StatusOr<std::vector<Rgb>> at_vertex = fit->AtPositions(*indirect);
  if (!at_vertex.ok()) return at_vertex.status();
  const GatherScene scene(mesh, caster, attributes, *std::move(at_vertex), false, camera);
  return RenderScene(scene, camera, PixelSamples{options.rays, 0}, options);
}

}  // namespace radflux
