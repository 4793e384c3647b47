#include "solver/formfactor/cell_detail.h"

#include <atomic>

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
  std::atomic<uint64_t> rays{0};
  ParallelFor(unknowns, 16, options.threads, [&](int64_t begin, int64_t end) {
    thread_local std::vector<StreamRay> stream;
    for (int64_t u = begin; u < end; ++u) {
      const uint32_t i = static_cast<uint32_t>(u);
      if (!context.needs_row[i]) continue;
      const uint32_t k = RowRayCount(options.rays, context.OpaqueArea(i), context.mean_row_area);
      const uint32_t points = PatternSeed(options.seed, i, kPointStream);
      const uint32_t directions = PatternSeed(options.seed, i, kDirectionStream);
      const UnknownPointSampler sample_point(*context.mesh, context.clusters, i);
      stream.resize(k);
      for (uint32_t r = 0; r < k; ++r) {
        stream[r] =
            context.CosineRay(sample_point(MultiJitteredSample(r, k, points)),
                              MultiJitteredSample(PermuteIndex(r, k, directions), k, directions));
      }
      context.caster->IntersectStream(stream);
      Rgb& h = detail.irradiance[i];
      const double weight = 1.0 / (k * context.Exposure(i));  // the exposed part's (exposed_area.h)
      for (const StreamRay& ray : stream) {
        const uint32_t hit = ray.FrontPatch();
        if (hit == kNoPatch) continue;
        const Rgb& delta = deviation[cells.of_patch[hit]];
        for (int b = 0; b < kBands; ++b) h[b] += weight * delta[b];
      }
      rays += k;
    }
  });
  detail.rays = rays;
  return detail;
}

}  // namespace radflux
