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

// One gather ray: the cell it starts on, the patch whose front it meets (kNoPatch: none), and
// whether it met a back side instead.
struct GatherHit {
  uint32_t from_cell = 0;
  uint32_t hit = kNoPatch;
  bool back = false;
};

}  // namespace

CellDetail GatherCellDetail(const RowContext& context, std::span<const Rgb> deviation,
                            const FormFactorOptions& options, const SolvedLight* solved) {
  const uint32_t unknowns = context.Unknowns();
  const PatchClusters& cells = *context.cells;
  // Each unknown's rays, stored at first[i] ..: cast once, read for I_c and then for H.
  std::vector<uint32_t> rays_of(unknowns, 0);
  std::vector<uint64_t> first(unknowns + 1, 0);
  for (uint32_t i = 0; i < unknowns; ++i) {
    if (context.needs_row[i]) {
      rays_of[i] = RowRayCount(options.rays, context.OpaqueArea(i), context.mean_row_area);
    }
    first[i + 1] = first[i] + rays_of[i];
  }
  std::vector<GatherHit> hits(first[unknowns]);
  ParallelFor(unknowns, 16, options.threads, [&](int64_t begin, int64_t end) {
    thread_local std::vector<StreamRay> stream;
    for (int64_t u = begin; u < end; ++u) {
      const uint32_t i = static_cast<uint32_t>(u), k = rays_of[i];
      if (k == 0) continue;
      const uint32_t points = PatternSeed(options.seed, i, kPointStream);
      const uint32_t directions = PatternSeed(options.seed, i, kDirectionStream);
      const UnknownPointSampler sample_point(*context.mesh, context.clusters, i);
      stream.resize(k);
      for (uint32_t r = 0; r < k; ++r) {
        const Point2 at = MultiJitteredSample(r, k, points);
        stream[r] = context.CosineRay(
            sample_point(at), MultiJitteredSample(PermuteIndex(r, k, directions), k, directions));
        hits[first[i] + r].from_cell = cells.of_patch[sample_point.MemberPatch(at.x)];
      }
      context.caster->IntersectStream(stream);
      for (uint32_t r = 0; r < k; ++r) {
        GatherHit& h = hits[first[i] + r];
        h.hit = stream[r].FrontPatch();
        h.back = h.hit == kNoPatch && stream[r].geom != kNoPatch;
      }
    }
  });
  CellDetail detail;
  std::vector<Rgb> delta(deviation.begin(), deviation.end());
  if (solved != nullptr) {
    // I_c per cell (sum, then mean over its rays), each group's cells written by one thread.
    std::vector<Rgb> indirect(cells.size(), Rgb{});
    std::vector<uint32_t> count(cells.size(), 0);
    std::atomic<uint64_t> indirect_cells{0};
    ParallelFor(unknowns, 64, options.threads, [&](int64_t begin, int64_t end) {
      for (int64_t u = begin; u < end; ++u) {
        const uint32_t g = static_cast<uint32_t>(u);
        const std::span<const uint32_t> own = context.CellsOf(g);
        if (own.size() < 2 || rays_of[g] == 0) continue;
        for (uint64_t r = first[g]; r < first[g + 1]; ++r) {
          const GatherHit& h = hits[r];
          if (h.back) continue;  // from a part enclosed in a solid (exposed_area.h): no one's
          ++count[h.from_cell];
          if (h.hit == kNoPatch) continue;
          const uint32_t j = context.UnknownOf(h.hit);
          if (context.emitter[j]) continue;  // the direct light: D_c's
          const Rgb& d = deviation[cells.of_patch[h.hit]];
          for (int b = 0; b < kBands; ++b)
            indirect[h.from_cell][b] += solved->radiosity[j][b] + d[b];
        }
        Rgb mean{};
        double area = 0;
        for (uint32_t c : own) {
          if (count[c] == 0) continue;
          for (int b = 0; b < kBands; ++b) indirect[c][b] /= count[c];
          area += cells.area[c];
          for (int b = 0; b < kBands; ++b) mean[b] += cells.area[c] * indirect[c][b];
        }
        for (uint32_t c : own) {
          if (count[c] == 0) continue;
          for (int b = 0; b < kBands; ++b) {
            delta[c][b] += solved->reflectance[g][b] * (indirect[c][b] - mean[b] / area);
          }
          ++indirect_cells;
        }
      }
    });
    detail.indirect_cells = indirect_cells;
  }
  detail.irradiance.assign(unknowns, Rgb{});
  ParallelFor(unknowns, 64, options.threads, [&](int64_t begin, int64_t end) {
    for (int64_t u = begin; u < end; ++u) {
      const uint32_t i = static_cast<uint32_t>(u);
      if (rays_of[i] == 0) continue;
      Rgb& h = detail.irradiance[i];
      const double weight = 1.0 / (rays_of[i] * context.Exposure(i));  // the exposed part's
      for (uint64_t r = first[i]; r < first[i + 1]; ++r) {             // (exposed_area.h)
        if (hits[r].hit == kNoPatch) continue;
        const Rgb& d = delta[cells.of_patch[hits[r].hit]];
        for (int b = 0; b < kBands; ++b) h[b] += weight * d[b];
      }
    }
  });
  detail.rays = first[unknowns];
  return detail;
}

}  // namespace radflux
