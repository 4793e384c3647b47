#include "solver/formfactor/cell_detail.h"

#include <atomic>
#include <unordered_map>

#include "solver/core/parallel.h"
#include "solver/core/sampling.h"

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

// Every unknown's rays, cast once and kept: unknown i's are hits[first[i] .. first[i + 1]).
struct GatherRays {
  std::vector<uint64_t> first;
  std::vector<GatherHit> hits;
};

GatherRays CastGatherRays(const RowContext& context, const FormFactorOptions& options) {
  const uint32_t unknowns = context.Unknowns();
  GatherRays out;
  out.first.assign(unknowns + 1, 0);
  for (uint32_t i = 0; i < unknowns; ++i) {
    out.first[i + 1] = out.first[i] + (context.needs_row[i] ? context.RowRays(i, options.rays) : 0);
  }
  out.hits.resize(out.first[unknowns]);
  ParallelFor(unknowns, 16, options.threads, [&](int64_t begin, int64_t end) {
    thread_local std::vector<StreamRay> stream;
    for (int64_t u = begin; u < end; ++u) {
      const uint32_t i = static_cast<uint32_t>(u);
      const uint32_t k = static_cast<uint32_t>(out.first[i + 1] - out.first[i]);
      if (k == 0) continue;
      GatherHit* hits = out.hits.data() + out.first[i];
      const uint32_t points = PatternSeed(options.seed, i, kPointStream);
      const uint32_t directions = PatternSeed(options.seed, i, kDirectionStream);
      const UnknownPointSampler sample_point(*context.mesh, context.clusters, i);
      stream.resize(k);
      for (uint32_t r = 0; r < k; ++r) {
        const Point2 at = MultiJitteredSample(r, k, points);
        stream[r] = context.CosineRay(
            sample_point(at), MultiJitteredSample(PermuteIndex(r, k, directions), k, directions));
        hits[r].from = sample_point.MemberPatch(at.x);
      }
      context.caster->IntersectStream(stream);
      for (uint32_t r = 0; r < k; ++r) {
        hits[r].hit = stream[r].FrontPatch();
        hits[r].back = hits[r].hit == kNoPatch && stream[r].geom != kNoPatch;
      }
    }
  });
  return out;
}

// Per scene face of one group: the light its counted rays met, summed, then their mean I_f.
struct FaceLight {
  Rgb light{};
  uint32_t rays = 0;
};
using FaceLights = std::unordered_map<uint32_t, FaceLight>;

// I_f of each face of group g from its rays (a ray that met a back side left a part enclosed
// in a solid and does not count; one that met an emitter brought direct light, D_c's).
void ReadFaceLights(const RowContext& context, std::span<const GatherHit> rays,
                    std::span<const Rgb> deviation, const SolvedLight& solved, FaceLights& faces) {
  faces.clear();
  for (const GatherHit& h : rays) {
    if (h.back) continue;
    FaceLight& light = faces[context.mesh->patches[h.from].face];
    ++light.rays;
    if (h.hit == kNoPatch) continue;
    const uint32_t j = context.UnknownOf(h.hit);
    if (context.emitter[j]) continue;
    const Rgb& d = deviation[context.cells->of_patch[h.hit]];
    for (int b = 0; b < kBands; ++b) light.light[b] += solved.radiosity[j][b] + d[b];
  }
  for (auto& [face, light] : faces) {
    for (int b = 0; b < kBands; ++b) light.light[b] /= light.rays;
  }
}

// rho_g (I_c - Ibar_g) into indirect[c] for each cell c of group g that has a read patch (a
// patch whose face has a counted ray); returns how many did.
uint32_t GroupIndirectDeviation(const RowContext& context, uint32_t g, const FaceLights& faces,
                                const SolvedLight& solved, std::vector<Rgb>& indirect) {
  const PatchClusters& cells = *context.cells;
  auto face_light = [&](uint32_t p) -> const FaceLight* {
    const auto it = faces.find(context.mesh->patches[p].face);
    return it == faces.end() ? nullptr : &it->second;
  };
  Rgb mean{};  // Ibar_g: over the group's read patches
  double read_area = 0;
  for (uint32_t c : context.CellsOf(g)) {
    for (uint32_t p : cells.Members(c)) {
      const FaceLight* light = face_light(p);
      if (light == nullptr) continue;
      const double a = context.mesh->patches[p].area;
      read_area += a;
      for (int b = 0; b < kBands; ++b) mean[b] += a * light->light[b];
    }
  }
  if (!(read_area > 0)) return 0;
  for (int b = 0; b < kBands; ++b) mean[b] /= read_area;
  uint32_t count = 0;
  for (uint32_t c : context.CellsOf(g)) {
    Rgb excess{};  // sum over the cell's read patches of A_p (I_p - Ibar_g)
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
    for (int b = 0; b < kBands; ++b) indirect[c][b] = solved.reflectance[g][b] * excess[b] / area;
    ++count;
  }
  return count;
}

}  // namespace

CellDetail GatherCellDetail(const RowContext& context, std::span<const Rgb> deviation,
                            const FormFactorOptions& options, const SolvedLight* solved) {
  const uint32_t unknowns = context.Unknowns();
  const PatchClusters& cells = *context.cells;
  const GatherRays rays = CastGatherRays(context, options);  // read for I_c, then for H
  auto rays_of = [&](uint32_t i) {
    return std::span<const GatherHit>(rays.hits).subspan(rays.first[i],
                                                         rays.first[i + 1] - rays.first[i]);
  };
  CellDetail detail;
  std::vector<Rgb> delta(deviation.begin(), deviation.end());
  if (solved != nullptr) {
    detail.indirect.assign(cells.size(), Rgb{});
    std::atomic<uint64_t> indirect_cells{0};
    ParallelFor(unknowns, 64, options.threads, [&](int64_t begin, int64_t end) {
      thread_local FaceLights faces;
      for (int64_t u = begin; u < end; ++u) {
        const uint32_t g = static_cast<uint32_t>(u);
        if (context.CellsOf(g).size() < 2 || rays_of(g).empty()) continue;
        ReadFaceLights(context, rays_of(g), deviation, *solved, faces);
        indirect_cells += GroupIndirectDeviation(context, g, faces, *solved, detail.indirect);
      }
    });
    detail.indirect_cells = indirect_cells;
    for (size_t c = 0; c < delta.size(); ++c) {
      for (int b = 0; b < kBands; ++b) delta[c][b] += detail.indirect[c][b];
    }
  }
  detail.irradiance.assign(unknowns, Rgb{});
  ParallelFor(unknowns, 64, options.threads, [&](int64_t begin, int64_t end) {
    for (int64_t u = begin; u < end; ++u) {
      const uint32_t i = static_cast<uint32_t>(u);
      if (rays_of(i).empty()) continue;
      Rgb& h = detail.irradiance[i];
      const double weight = 1.0 / (rays_of(i).size() * context.Exposure(i));  // the exposed
      for (const GatherHit& ray : rays_of(i)) {                               // part's
        if (ray.hit == kNoPatch) continue;                                    // (exposed_area.h)
        const Rgb& d = delta[cells.of_patch[ray.hit]];
        for (int b = 0; b < kBands; ++b) h[b] += weight * d[b];
      }
    }
  });
  detail.rays = rays.first[unknowns];
  return detail;
}

}  // namespace radflux
