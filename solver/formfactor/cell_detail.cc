#include "solver/formfactor/cell_detail.h"

#include <atomic>
#include <unordered_map>

#include "solver/core/parallel.h"
#include "solver/core/sampling.h"
#include "solver/formfactor/row_rays.h"

namespace radflux {
namespace {

// Pattern streams of the gather's points and directions, apart from every row's.
constexpr uint64_t kPointStream = 23;
constexpr uint64_t kDirectionStream = 29;

// One gather ray: the patch it starts on, the patch whose front it meets (kNoPatch: none), and
// whether it met a back side instead.
struct GatherHit {
  uint32_t from = 0;
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
      rays_of[i] =
          RowRayCount(options.rays, context.OpaqueArea(i), context.mean_row_area, context.Emits(i));
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
        hits[first[i] + r].from = sample_point.MemberPatch(at.x);
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
    detail.indirect.assign(cells.size(), Rgb{});
    // Per group (one thread each): the mean over each of its faces' counted rays, then each
    // cell's area-weighted mean over its patches (a patch of a face without a counted ray
    // reads the group's mean) and the group's mean over its read patches.
    std::atomic<uint64_t> indirect_cells{0};
    ParallelFor(unknowns, 64, options.threads, [&](int64_t begin, int64_t end) {
      struct FaceLight {
        Rgb light{};  // the sum over the face's counted rays, then their mean: I_f
        uint32_t rays = 0;
      };
      thread_local std::unordered_map<uint32_t, FaceLight> faces;  // by scene face
      for (int64_t u = begin; u < end; ++u) {
        const uint32_t g = static_cast<uint32_t>(u);
        const std::span<const uint32_t> own = context.CellsOf(g);
        if (own.size() < 2 || rays_of[g] == 0) continue;
        faces.clear();
        for (uint64_t r = first[g]; r < first[g + 1]; ++r) {
          const GatherHit& h = hits[r];
          if (h.back) continue;  // from a part enclosed in a solid (exposed_area.h): no one's
          FaceLight& light = faces[context.mesh->patches[h.from].face];
          ++light.rays;
          if (h.hit == kNoPatch) continue;
          const uint32_t j = context.UnknownOf(h.hit);
          if (context.emitter[j]) continue;  // the direct light: D_c's
          const Rgb& d = deviation[cells.of_patch[h.hit]];
          for (int b = 0; b < kBands; ++b) light.light[b] += solved->radiosity[j][b] + d[b];
        }
        Rgb mean{};
        double read_area = 0;
        for (auto& [face, light] : faces) {
          for (int b = 0; b < kBands; ++b) light.light[b] /= light.rays;
        }
        auto face_light = [&](uint32_t p) -> const FaceLight* {
          const auto it = faces.find(context.mesh->patches[p].face);
          return it == faces.end() ? nullptr : &it->second;
        };
        for (uint32_t c : own) {
          for (uint32_t p : cells.Members(c)) {
            const FaceLight* light = face_light(p);
            if (light == nullptr) continue;
            const double a = context.mesh->patches[p].area;
            read_area += a;
            for (int b = 0; b < kBands; ++b) mean[b] += a * light->light[b];
          }
        }
        if (!(read_area > 0)) continue;
        for (int b = 0; b < kBands; ++b) mean[b] /= read_area;
        for (uint32_t c : own) {
          Rgb excess{};  // sum over the cell's read patches of A_p (I_p - mean)
          double area = 0;
          bool read = false;
          for (uint32_t p : cells.Members(c)) {
            const double a = context.mesh->patches[p].area;
            area += a;
            const FaceLight* light = face_light(p);
            if (light == nullptr) continue;
            read = true;
            for (int b = 0; b < kBands; ++b) excess[b] += a * (light->light[b] - mean[b]);
          }
          if (!read) continue;
          for (int b = 0; b < kBands; ++b) {
            detail.indirect[c][b] = solved->reflectance[g][b] * excess[b] / area;
            delta[c][b] += detail.indirect[c][b];
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
