#include "solver/output/indirect_regather.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "solver/core/parallel.h"
#include "solver/core/sampling.h"
#include "solver/formfactor/row_builder.h"
#include "solver/output/render.h"

namespace radflux {
namespace {

// Pattern streams of a patch's points and directions, apart from the pictures' and the rows'.
constexpr uint64_t kPointStream = 47;
constexpr uint64_t kDirectionStream = 53;
// Patches per block of rays traced together.
constexpr int64_t kPatchesPerBlock = 16;

// The rays of a patch that `pixels` pixel centres see (0 for none).
size_t RaysFor(uint32_t pixels) {
  if (pixels == 0) return 0;
  const uint64_t rays = static_cast<uint64_t>(pixels) * kRegatherRaysPerPixel;
  return static_cast<size_t>(std::clamp<uint64_t>(rays, kRegatherLeastRays, kRegatherMostRays));
}

// Sets up the rays of patch p from stratified points of its area (its own shift of shared
// multi-jittered sets, point k paired with direction k) into `out`.
void PatchRays(const PatchMesh& mesh, uint32_t p, uint64_t seed, double epsilon,
               std::vector<Point2>& points, std::vector<Point2>& directions,
               std::span<StreamRay> out) {
  const Patch& patch = mesh.patches[p];
  const PatchPointSampler sample(mesh, p);
  const Frame frame = Frame::FromNormal(patch.normal);
  points.resize(out.size());
  directions.resize(out.size());
  ShiftedMultiJitteredSamples(PatternSeed(seed, p, kPointStream), kPointStream, points);
  ShiftedMultiJitteredSamples(PatternSeed(seed, p, kDirectionStream), kDirectionStream, directions);
  for (size_t k = 0; k < out.size(); ++k) {
    StreamRay& r = out[k];
    r = StreamRay{};
    r.SetOrigin(sample(points[k]) + patch.normal * epsilon);
    r.SetDirection(frame.ToWorld(SampleCosineHemisphere(directions[k])));
  }
}

}  // namespace

absl::StatusOr<std::vector<Rgb>> ReflectedAtVertices(const PatchMesh& mesh, const VertexFit& fit,
                                                     const PatchAttributes& attributes,
                                                     const std::vector<Rgb>& patch_radiosity) {
  if (patch_radiosity.size() != mesh.size() || attributes.size() != mesh.size()) {
    return absl::InvalidArgumentError(absl::StrCat("reflected radiosity: ", patch_radiosity.size(),
                                                   " radiosities and ", attributes.size(),
                                                   " attributes for ", mesh.size(), " patches"));
  }
  std::vector<Rgb> reflected(mesh.size());
  for (size_t p = 0; p < mesh.size(); ++p) {
    for (int b = 0; b < kBands; ++b) {
      reflected[p][b] = patch_radiosity[p][b] - attributes.emission[p][b];
    }
  }
  return fit.AtPositions(reflected);
}

Rgb SumMetReflected(const PatchMesh& mesh, const std::vector<Rgb>& at_vertex,
                    std::span<const StreamRay> rays) {
  Rgb sum{};
  for (const StreamRay& ray : rays) {
    const uint32_t q = ray.FrontPatch();
    if (q == kNoPatch || q >= mesh.size()) continue;
    Hit hit;
    hit.patch = q;
    hit.u = ray.u;
    hit.v = ray.v;
    const Rgb r = InterpolateAtHit(mesh, at_vertex, hit);
    for (int b = 0; b < kBands; ++b) sum[b] += std::max(0.0, r[b]);
  }
  return sum;
}

std::vector<uint32_t> PixelsPerPatch(const PatchMesh& mesh, const RayCaster& caster,
                                     const Camera& camera, int threads) {
  const PinholeProjection projection(camera);
  std::vector<uint32_t> pixels(mesh.size(), 0);
  std::vector<std::vector<uint32_t>> seen(static_cast<size_t>(camera.height));
  ParallelFor(camera.height, 1, threads, [&](int64_t begin, int64_t end) {
    std::vector<StreamRay> row(static_cast<size_t>(camera.width));
    for (int64_t y = begin; y < end; ++y) {
      for (int x = 0; x < camera.width; ++x) {
        const Ray ray = projection.RayThrough(x + 0.5, static_cast<double>(y) + 0.5);
        row[static_cast<size_t>(x)] = StreamRay{};
        row[static_cast<size_t>(x)].SetOrigin(ray.origin);
        row[static_cast<size_t>(x)].SetDirection(ray.direction);
      }
      caster.IntersectStream(row);
      for (const StreamRay& r : row) {
        const uint32_t p = r.FrontPatch();
        if (p != kNoPatch && p < mesh.size()) seen[static_cast<size_t>(y)].push_back(p);
      }
    }
  });
  for (const std::vector<uint32_t>& row : seen) {
    for (uint32_t p : row) ++pixels[p];
  }
  return pixels;
}

absl::StatusOr<std::vector<Rgb>> RegatherShownIndirect(
    const PatchMesh& mesh, const VertexFit& fit, const RayCaster& caster,
    const PatchAttributes& attributes, const std::vector<Rgb>& patch_radiosity,
    const std::vector<Rgb>& patch_indirect, const Camera& camera, uint64_t seed, int threads) {
  if (patch_radiosity.size() != mesh.size() || patch_indirect.size() != mesh.size() ||
      attributes.size() != mesh.size()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "indirect regather: ", patch_radiosity.size(), " radiosities, ", patch_indirect.size(),
        " indirect values and ", attributes.size(), " attributes for ", mesh.size(), " patches"));
  }
  absl::StatusOr<std::vector<Rgb>> reflected =
      ReflectedAtVertices(mesh, fit, attributes, patch_radiosity);
  if (!reflected.ok()) return reflected.status();

  const std::vector<uint32_t> pixels = PixelsPerPatch(mesh, caster, camera, threads);
  const double epsilon = RayEpsilonFor(mesh);
  std::vector<Rgb> indirect = patch_indirect;
  ParallelFor(static_cast<int64_t>(mesh.size()), kPatchesPerBlock, threads,
              [&](int64_t begin, int64_t end) {
                thread_local std::vector<StreamRay> stream;
                thread_local std::vector<Point2> points, directions;
                std::vector<size_t> first(static_cast<size_t>(end - begin) + 1, 0);
                for (int64_t p = begin; p < end; ++p) {
                  first[p - begin + 1] = first[p - begin] + RaysFor(pixels[p]);
                }
                stream.resize(first.back());
                for (int64_t p = begin; p < end; ++p) {
                  const size_t n = first[p - begin + 1] - first[p - begin];
                  if (n == 0) continue;
                  PatchRays(mesh, static_cast<uint32_t>(p), seed, epsilon, points, directions,
                            std::span<StreamRay>(stream).subspan(first[p - begin], n));
                }
                caster.IntersectStream(stream);
                for (int64_t p = begin; p < end; ++p) {
                  const size_t from = first[p - begin], to = first[p - begin + 1];
                  if (from == to) continue;
                  const Rgb sum =
                      SumMetReflected(mesh, *reflected,
                                      std::span<const StreamRay>(stream).subspan(from, to - from));
                  const Rgb& rho = attributes.reflectance[p];
                  for (int b = 0; b < kBands; ++b) {
                    indirect[p][b] = rho[b] * sum[b] / static_cast<double>(to - from);
                  }
                }
              });
  return indirect;
}

}  // namespace radflux
