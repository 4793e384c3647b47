// monte_carlo: k_i cosine-weighted rays from stratified points on patch i (k on average,
// in proportion to the patch's area: row_rays.h); each ray that hits the front of a patch j
// that does not emit adds 1/k_i to F_ij (an emitter's row: of any patch j). Emitter columns
// of the other rows come from light sampling (their direct light would be the noisiest
// term): a fixed budget of light samples per row,
// whatever the number of emitter patches, combined by multiple importance sampling with the
// cosine rays that hit emitters which fill much of the hemisphere (light_sampling.h); the
// other hits on emitters count for nothing, so nothing is counted twice. A group with
// direct-light cells takes its emitter columns from its cells' light samples instead
// (cell_direct.h: 4 times a row's budget, stratified over the cells), the very estimate that
// spreads its direct light over its patches after the solve. Entries towards
// hidden unknowns (slots) come from their own rows by reciprocity (reciprocal_columns.h).
// Once all rows are built, each pair of rows averages its two estimates of the pair's
// exchange (reciprocal_pairs.h, FinishRows in memory or in a store).
#include <map>
#include <optional>
#include <vector>

#include "solver/core/sampling.h"
#include "solver/formfactor/bright_reflectors.h"
#include "solver/formfactor/builders.h"
#include "solver/formfactor/light_sampling.h"
#include "solver/formfactor/reciprocal_columns.h"
#include "solver/formfactor/reciprocal_pairs.h"
#include "solver/formfactor/row_rays.h"

namespace radflux {
namespace {

constexpr uint64_t kShiftStream = 11;
constexpr uint32_t kPositionPattern = 0x2545f491u;
constexpr uint32_t kDirectionPattern = 0x9e3779b9u;

// The k position samples and k paired direction samples of a row with k rays: one
// correlated multi-jittered set.
struct RaySet {
  std::vector<Point2> positions;
  std::vector<float> direction_x, direction_y;  // the unshifted direction samples, in float
};

RaySet MakeRaySet(uint32_t k) {
  RaySet set;
  for (uint32_t r = 0; r < k; ++r) {
    set.positions.push_back(MultiJitteredSample(r, k, kPositionPattern));
    const Point2 d =
        MultiJitteredSample(PermuteIndex(r, k, kDirectionPattern), k, kDirectionPattern);
    set.direction_x.push_back(static_cast<float>(d.x));
    set.direction_y.push_back(static_cast<float>(d.y));
  }
  return set;
}

// `lit` (WithBrightReflectors(context)) with only its bright reflectors as emitter columns.
RowContext OnlyBrightReflectors(const RowContext& lit, const RowContext& context) {
  RowContext out = lit;
  for (uint32_t j = 0; j < out.emitter.size(); ++j) {
    if (context.emitter[j]) out.emitter[j] = 0;
  }
  return out;
}

class MonteCarloBuilder final : public RowBuilder {
 public:
  // One ray set per row size in use, computed once; each patch shifts its set toroidally by
  // its own random offsets (Cranley-Patterson rotation), which keeps it stratified and
  // makes the estimate unbiased at a few additions per ray.
  MonteCarloBuilder(const RowContext& context, const FormFactorOptions& options)
      : context_(context),
        options_(options),
        lit_(WithBrightReflectors(context)),
        reflectors_(OnlyBrightReflectors(lit_, context)),
        lights_(context),
        bright_lights_(lit_, &lights_),
        reflector_lights_(reflectors_, &lights_) {
    sets_.emplace(Rays(0), MakeRaySet(Rays(0)));  // a context without unknowns' areas
    for (uint32_t u = 0; u < context.needs_row.size(); ++u) {
      const uint32_t k = Rays(u);
      if (!sets_.contains(k)) sets_.emplace(k, MakeRaySet(k));
    }
    // While the hidden unknowns' rows are built, hidden_ is empty: they keep their own hits.
    hidden_ =
        ReciprocalColumns(context, options.rays, options.threads,
                          [this](uint32_t j, RowAccumulator& row) { return SampleRow(j, row); });
    // The pairs of rows whose columns are cosine rays' alone: neither light sampled nor a
    // hidden unknown (whose pairs are exactly reciprocal already: reciprocal_columns.h).
    if (options.reciprocal_pairs) {
      std::vector<uint8_t> cosine(context.Unknowns());
      for (uint32_t u = 0; u < cosine.size(); ++u) {
        cosine[u] = context.needs_row[u] && !lit_.emitter[u] && !hidden_.Hidden(u) ? 1 : 0;
      }
      pairs_.emplace(context, options.rays, cosine);
    }
  }

  uint64_t BuildRow(uint32_t i, RowAccumulator& row) const override {
    if (hidden_.Hidden(i)) return hidden_.AddOwnRow(i, row);
    return SampleRow(i, row);
  }

  const ReciprocalPairs* Pairs() const override { return pairs_ ? &*pairs_ : nullptr; }

 private:
  // Row i from its own rays and light samples, but for the columns hidden_ fills.
  uint64_t SampleRow(uint32_t i, RowAccumulator& row) const {
    const uint32_t shift = PatternSeed(options_.seed, i, kShiftStream);
    const Point2 ps = RandomShift(shift, 0);
    const Point2 ds = RandomShift(shift, 2);
    const RaySet& set = sets_.at(Rays(i));
    // Per-thread scratch, reused row to row: the rays, and their origins on i before the lift.
    thread_local std::vector<StreamRay> stream;
    thread_local std::vector<SurfacePoint> origins;
    thread_local std::vector<LightSampler::CosineHit> emitter_hits;
    stream.resize(set.positions.size());
    origins.resize(set.positions.size());
    emitter_hits.clear();
    if (context_.SinglePatch(i)) {
      PatchRays(context_.FirstPatch(i), set, ps, ds, stream, origins);
    } else {
      GroupRays(i, set, ps, ds, stream, origins);
    }
    context_.caster->IntersectStream(stream);
    // A row that is itself light sampled (an emitter's, a bright reflector's) carries much
    // power in the energy balance: its cosine rays keep the bright reflectors' columns, so
    // that its sum stays one multinomial draw (light_sampling.h), not two independent parts.
    const bool plain = lit_.emitter[i] != 0;
    // An emitter's row keeps the emitters' columns too: all of it is its cosine rays, and it
    // casts no light samples. Its B is mostly its own E, so the light other emitters give it
    // needs no light sampling; and where emitters face each other closely (the conference
    // room's fixtures, emitting faces with rho = 0.98 lining a reflector) the light samples'
    // near-field noise took rows to sums of 1.39, the row-sum cap removed 1.25% of the room's
    // light and the fixtures' many bounces made their B swing with the seed.
    const bool emitter_row = context_.emitter[i] != 0;
    // A group with direct-light cells: the emitter columns come from the cells, its own light
    // samples and cosine hits estimate the bright reflectors' alone.
    const bool from_cells = context_.CellsOf(i).size() > 1;
    const RowContext& columns = plain ? context_ : from_cells ? reflectors_ : lit_;
    const LightSampler& lights = plain ? lights_ : from_cells ? reflector_lights_ : bright_lights_;
    const double weight = 1.0 / static_cast<double>(set.positions.size());
    // A group that is not flat sees itself (F_ii > 0, Galerkin's diagonal: face_grouping.h);
    // a single patch is flat and cannot.
    const bool group = !context_.SinglePatch(i);
    for (size_t r = 0; r < stream.size(); ++r) {
      const uint32_t hit = stream[r].FrontPatch();  // a back side absorbs the ray
      if (hit == kNoPatch) continue;
      const uint32_t j = context_.UnknownOf(hit);
      if (j == i && !group) continue;
      if (columns.emitter[j] && !emitter_row) {
        emitter_hits.push_back({origins[r].x, origins[r].n, j});
      } else if (from_cells && context_.emitter[j]) {
        continue;
      } else if (!hidden_.Fills(i, j)) {
        row.Add(j, weight);
      }
    }
    hidden_.AddColumns(i, row);
    // A group's irradiance varies across its members far more than across one patch (some
    // face a lamp, some do not): its light samples each take a point of their own, so the
    // budget is spread over the whole group instead of a few spots that mostly miss the lit ones.
    const int per_point = group ? 1 : kLightSamplesAtAPoint;
    uint64_t light_rays = emitter_row ? 0
                                      : lights.AddEmitterColumns(
                                            i, options_.samples * (kLightSamplesPerS / per_point),
                                            per_point, options_.seed, row, emitter_hits,
                                            static_cast<uint32_t>(stream.size()), AreaShare(i));
    if (from_cells) {
      light_rays +=
          lights_.AddGroupEmitterColumns(i, CellLightSamplesPerGroup(options_), options_.seed, row);
    }
    // The light samples' part of the emitter columns varies apart from the cosine rays'
    // part of the row: where emitters fill much of the hemisphere their noise can add up to
    // more than 1. Only a row that would then return more light
    // than kMaxRowGain is scaled back (rho F B must converge for every rho < 1): scaling
    // every row above 1 cut the upper half of a closed room's rows' noise (they sum to 1 in
    // expectation) and made B 1.1% low in a closed cube at k = 64 (3% at k = 16).
    // What that removes is kept (RowAccumulator::ScaledOff) for the energy balance, which
    // books it as a term of its own.
    // Rays and light samples from the enclosed part of the unknown found nothing: the row
    // is its exposed part's (exposed_area.h).
    if (const double exposure = context_.Exposure(i); exposure < 1) row.Scale(1 / exposure);
    row.CapSum(context_.MaxRowSum(i));
    return stream.size() + light_rays;
  }

  // Unknown u's area against the mean row's (row_rays.h): its near-field light points follow it.
  double AreaShare(uint32_t u) const {
    return RowAreaShare(context_.OpaqueArea(u), context_.mean_row_area);
  }

  // Unknown u's rays (row_rays.h).
  uint32_t Rays(uint32_t u) const { return context_.RowRays(u, options_.rays); }

  // The rays of `set` from one patch p, shifted by (ps, ds), and their origins on p.
  void PatchRays(uint32_t p, const RaySet& set, Point2 ps, Point2 ds,
                 std::vector<StreamRay>& stream, std::vector<SurfacePoint>& origins) const {
    const PatchMesh& mesh = *context_.mesh;
    const Patch& patch = mesh.patches[p];
    const Frame frame = Frame::FromNormal(patch.normal);
    const Vec3 lift = patch.normal * context_.ray_epsilon;
    const size_t k = set.positions.size();
    // The k directions first, in float and in a loop of their own, which GCC vectorises
    // (this file is built with -fno-math-errno for the sqrt): per-thread scratch, x then y
    // then z, reused row to row.
    thread_local std::vector<float> directions;
    directions.resize(3 * k);
    float* __restrict wx = directions.data();
    float* __restrict wy = wx + k;
    float* __restrict wz = wy + k;
    const float* ux = set.direction_x.data();
    const float* uy = set.direction_y.data();
    const float dsx = static_cast<float>(ds.x), dsy = static_cast<float>(ds.y);
    const auto f = [](double v) { return static_cast<float>(v); };
    const float sx = f(frame.s.x), sy = f(frame.s.y), sz = f(frame.s.z);
    const float tx = f(frame.t.x), ty = f(frame.t.y), tz = f(frame.t.z);
    const float nx = f(frame.n.x), ny = f(frame.n.y), nz = f(frame.n.z);
    for (size_t r = 0; r < k; ++r) {
      float x, y, z;
      CosineHemisphereDirection(WrapShift(ux[r], dsx), WrapShift(uy[r], dsy), x, y, z);
      wx[r] = sx * x + tx * y + nx * z;
      wy[r] = sy * x + ty * y + ny * z;
      wz[r] = sz * x + tz * y + nz * z;
    }
    const PatchPointSampler sample_point(mesh, p);
    for (size_t r = 0; r < k; ++r) {
      StreamRay& ray = stream[r];
      origins[r] = {sample_point(CranleyPattersonShift(set.positions[r], ps)), patch.normal};
      ray.SetOrigin(origins[r].x + lift);
      ray.dir_x = wx[r], ray.dir_y = wy[r], ray.dir_z = wz[r];
      ray.ResetHit();
    }
  }

  // The rays of `set` from a group of patches: each ray's origin is drawn over the members
  // by area (UnknownPointSampler) and its direction is cosine-weighted about that member's
  // normal; their origins into `origins`.
  void GroupRays(uint32_t u, const RaySet& set, Point2 ps, Point2 ds,
                 std::vector<StreamRay>& stream, std::vector<SurfacePoint>& origins) const {
    const UnknownPointSampler sample_point(*context_.mesh, context_.clusters, u);
    for (size_t r = 0; r < set.positions.size(); ++r) {
      const SurfacePoint& at = origins[r] =
          sample_point(CranleyPattersonShift(set.positions[r], ps));
      stream[r] = context_.CosineRay(at, {WrapShift(double{set.direction_x[r]}, ds.x),
                                          WrapShift(double{set.direction_y[r]}, ds.y)});
    }
  }

  const RowContext& context_;
  FormFactorOptions options_;
  RowContext lit_;                        // context_ with its bright reflectors as emitter columns
  RowContext reflectors_;                 // ... with its bright reflectors alone
  LightSampler lights_;                   // the emitter columns
  LightSampler bright_lights_;            // the emitter and bright reflector columns
  LightSampler reflector_lights_;         // the bright reflector columns
  std::map<uint32_t, RaySet> sets_;       // by rays per row
  ReciprocalColumns hidden_;              // the rows' entries towards hidden unknowns
  std::optional<ReciprocalPairs> pairs_;  // options.reciprocal_pairs: the rows' averaging
};

}  // namespace

std::unique_ptr<RowBuilder> MakeMonteCarloBuilder(const RowContext& context,
                                                  const FormFactorOptions& options) {
  return std::make_unique<MonteCarloBuilder>(context, options);
}

}  // namespace radflux
