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
#include "solver/output/render.h"
#include "solver/output/vertex_radiosity.h"

namespace radflux {
namespace {

// Pattern streams of a pixel's samples, apart from each other and from the light sampler's.
constexpr uint64_t kPixelStream = 31;
constexpr uint64_t kLightStream = 32;
constexpr uint64_t kGatherStream = 33;
// Paths per visible point: a pixel's N paths go through P = max(min(N, 16), ceil(N / 2))
// points (one primary ray each; at least 16 keep the pixel's footprint sampled as finely as
// before), a point's light samples sharing one set-up of the light sampler. Point j takes the
// pixel's paths j, j + P, ... (strided through the pixel's multi-jittered light and gather
// patterns, so that a point's samples are spread, not in one row of the pattern).
constexpr int kPathsPerPoint = 2;
constexpr int kMinPointsPerPixel = 16;

// The visible points of a pixel of N = rays paths.
int PointsPerPixel(int rays) {
  return std::max(std::min(rays, kMinPointsPerPixel),
                  (rays + kPathsPerPoint - 1) / kPathsPerPoint);
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
  // One visible point of a pixel: the patch it sees, and the ranges of its paths' light
  // samples and gather rays among the row's (light samples whose emitter cannot be seen
  // from the point cast no ray and add nothing).
  struct Point {
    uint32_t patch = kNoPatch;
    size_t light_begin = 0, light_end = 0, gather_begin = 0, gather_end = 0;
  };
  // The row's light and gather rays, and the light samples' estimates.
  struct Secondary {
    std::vector<StreamRay> light_rays, gather_rays;
    std::vector<LightSampler::PendingSample> pending;
  };
  // Casts the row's primary rays, one per visible point, into `primary`.
  void CastPrimary(int y, int rays, uint64_t seed, int width,
                   std::vector<StreamRay>& primary) const;
  // Sets up the paths of each point that sees a patch: their light samples and gather rays,
  // into `secondary`.
  void StartPaths(int y, int rays, uint64_t seed, std::span<const StreamRay> primary,
                  std::vector<Point>& points, Secondary& secondary) const;
  // The sum of the radiances that the paths of `point` estimate, given their traced light and
  // gather rays.
  Rgb PointRadiance(const Point& point, const Secondary& secondary) const;

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
  const int points = PointsPerPixel(rays);
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
  Rgb irradiance{};  // the paths' H_direct + H_indirect summed, W/m^2 per band
  for (size_t i = point.light_begin; i < point.light_end; ++i) {
    if (secondary.light_rays[i].Occluded()) continue;
    const LightSampler::PendingSample& sample = secondary.pending[i];
    const Rgb& e = lights_.emission[sample.emitter];
    for (int b = 0; b < kBands; ++b) irradiance[b] += e[b] * sample.form_factor;
  }
  for (size_t i = point.gather_begin; i < point.gather_end; ++i) {
    const StreamRay& g = secondary.gather_rays[i];
    const uint32_t q = g.FrontPatch();
    if (q == kNoPatch || q >= mesh_.size()) continue;
    Hit hit;
    hit.patch = q;
    hit.u = g.u;
    hit.v = g.v;
    const Rgb r = InterpolateAtHit(mesh_, reflected_at_vertex_, hit);
    for (int b = 0; b < kBands; ++b) irradiance[b] += std::max(0.0, r[b]);
  }
  const double paths = static_cast<double>(point.gather_end - point.gather_begin);
  const Rgb& rho = attributes_.reflectance[point.patch];
  const Rgb& e = attributes_.emission[point.patch];
  Rgb radiance;
  for (int b = 0; b < kBands; ++b) {
    radiance[b] = (paths * e[b] + rho[b] * irradiance[b]) * std::numbers::inv_pi;
  }
  return radiance;
}

void GatherScene::StartPaths(int y, int rays, uint64_t seed, std::span<const StreamRay> primary,
                             std::vector<Point>& points, Secondary& secondary) const {
  const int per_pixel = PointsPerPixel(rays);
  const int width = static_cast<int>(primary.size()) / per_pixel;
  std::vector<Point2> light_points(static_cast<size_t>(rays)), gather_points(light_points);
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
      std::array<Point2, kPathsPerPoint> directions;
      size_t paths = 0;
      for (int k = j; k < rays; k += per_pixel) directions[paths++] = light_points[k];
      Point& point = points[at];
      point.patch = p;
      point.light_begin = secondary.light_rays.size();
      sampler_.SamplePoint(x_on_p, patch.normal, lights_.of_patch[p], seed, pixel,
                           static_cast<uint32_t>(j * kPathsPerPoint),
                           std::span<const Point2>(directions).first(paths),
                           secondary.light_rays, secondary.pending);
      point.light_end = secondary.light_rays.size();
      point.gather_begin = secondary.gather_rays.size();
      const Frame frame = Frame::FromNormal(patch.normal);
      for (int k = j; k < rays; k += per_pixel) {
        StreamRay g;
        g.SetOrigin(x_on_p + patch.normal * light_context_.ray_epsilon);
        g.SetDirection(frame.ToWorld(SampleCosineHemisphere(gather_points[k])));
        secondary.gather_rays.push_back(g);
      }
      point.gather_end = secondary.gather_rays.size();
    }
  }
}

void GatherScene::Row(int y, int rays, uint64_t seed, Image& image) const {
  // Per-thread scratch, reused row to row (fresh vectors of this size cost page faults).
  thread_local std::vector<StreamRay> primary;
  thread_local std::vector<Point> points;
  thread_local Secondary secondary;
  CastPrimary(y, rays, seed, image.width, primary);
  points.assign(primary.size(), Point{});
  secondary.light_rays.clear();
  secondary.gather_rays.clear();
  secondary.pending.clear();
  StartPaths(y, rays, seed, primary, points, secondary);
  caster_.OccludedStream(secondary.light_rays);
  caster_.IntersectStream(secondary.gather_rays);
  const int per_pixel = PointsPerPixel(rays);
  for (int x = 0; x < image.width; ++x) {
    Rgb sum{};
    for (int j = 0; j < per_pixel; ++j) {
      const Point& point = points[static_cast<size_t>(x) * per_pixel + j];
      if (point.patch == kNoPatch) continue;
      const Rgb radiance = PointRadiance(point, secondary);
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
