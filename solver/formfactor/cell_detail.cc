#include "solver/formfactor/cell_detail.h"

#include "solver/core/parallel.h"
#include "solver/core/sampling.h"
#include "solver/formfactor/row_rays.h"

namespace radflux {
namespace {

// Pattern streams of the gather's points and directions, apart from every row's.
constexpr uint64_t kPointStream = 23;
constexpr uint64_t kDirectionStream = 29;

}  // namespace

CellDetail GatherCellDetail(const RowContext& context, std::span<const Rgb> deviation,
                            const FormFactorOptions& options) {
  const uint32_t unknowns = context.Unknowns();
  const PatchClusters& cells = *context.cells;
  CellDetail detail;
  detail.irradiance.assign(unknowns, Rgb{});
  const int threads = ThreadCount(options.threads);
  std::vector<uint64_t> rays(static_cast<size_t>(std::max(threads, DefaultThreadCount())), 0);
  ParallelFor(unknowns, 16, options.threads, [&](int64_t begin, int64_t end) {
    thread_local std::vector<StreamRay> stream;
    for (int64_t u = begin; u < end; ++u) {
      const uint32_t i = static_cast<uint32_t>(u);
      if (!context.needs_row[i]) continue;
      const double area = i < context.opaque_area.size() ? context.opaque_area[i] : 0;
      const uint32_t k = RowRayCount(options.rays, area, context.mean_row_area);
      const uint32_t points = PatternSeed(options.seed, i, kPointStream);
      const uint32_t directions = PatternSeed(options.seed, i, kDirectionStream);
      const UnknownPointSampler sample_point(*context.mesh, context.clusters, i);
      stream.assign(k, StreamRay{});
      for (uint32_t r = 0; r < k; ++r) {
        const SurfacePoint at = sample_point(MultiJitteredSample(r, k, points));
        const Point2 d = MultiJitteredSample(PermuteIndex(r, k, directions), k, directions);
        stream[r].SetOrigin(at.x + at.n * context.ray_epsilon);
        stream[r].SetDirection(Frame::FromNormal(at.n).ToWorld(SampleCosineHemisphere(d)));
      }
      context.caster->IntersectStream(stream);
      Rgb& h = detail.irradiance[i];
      const double weight = 1.0 / k;
      for (const StreamRay& ray : stream) {
        const uint32_t hit = ray.FrontPatch();
        if (hit == kNoPatch) continue;
        const Rgb& delta = deviation[cells.of_patch[hit]];
        for (int b = 0; b < kBands; ++b) h[b] += weight * delta[b];
      }
      rays[static_cast<size_t>(ThreadIndex())] += k;
    }
  });
  for (uint64_t r : rays) detail.rays += r;
  return detail;
}

}  // namespace radflux
