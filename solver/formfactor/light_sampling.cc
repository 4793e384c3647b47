#include "solver/formfactor/light_sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <vector>

#include "solver/core/sampling.h"
#include "solver/formfactor/row_rays.h"

namespace radflux {
namespace {

// Pattern streams of the light samples, apart from every other use of (seed, i).
constexpr uint64_t kLightPointStream = 21;
constexpr uint64_t kLightChoiceStream = 22;
constexpr uint64_t kLightDirectionStream = 23;
constexpr uint64_t kRejectionStream = 24;
// Cells' sample patterns apart from the rows' (which are seeded from (seed, unknown)).
constexpr uint64_t kCellSeed = 0xce11d1ec7ull;

// From this unoccluded form factor on, a light sample's direction is drawn exactly in
// proportion to the receiver's cosine within the emitter (cosine-weighted directions until
// one meets it: 1 / F tries on average), and combined with the row's cosine rays that meet
// it (light_sampling.h): its estimate is then free of the spread of cos / pdf, which is
// large where an emitter fills much of the hemisphere. Below it the emitter is small, the
// cosine varies little across it, and the warped solid-angle sample is used alone. A sample
// whose kMaxTries directions all miss (probability (1 - F)^kMaxTries < 1e-35) is lost.
constexpr double kRejectionFormFactor = 0.02;
constexpr int kMaxTries = 4096;

// A cosine-weighted direction around frame.n that meets the emitter, by rejection; the
// point it meets into `point`. False when kMaxTries directions miss.
bool CosineDirectionOnEmitter(const EmitterShape& emitter, const Vec3& x, const Frame& frame,
                              uint32_t pattern, Vec3& point) {
  for (uint32_t t = 0; t < kMaxTries; ++t) {
    const Vec3 w = frame.ToWorld(
        SampleCosineHemisphere({RandomFloat(2 * t, pattern), RandomFloat(2 * t + 1, pattern)}));
    if (EmitterHit(emitter, x, w, point)) return true;
  }
  return false;
}

// F_s(x) of `shape` when it may reach kRejectionFormFactor (its exact value), else -1 when
// its bound (ReachOf) already says it does not.
double RejectionFormFactor(const EmitterShape& shape, const Vec3& x, const Vec3& n) {
  if (ReachOf(shape, x).max_form_factor < kRejectionFormFactor) return -1;
  return EmitterFormFactor(shape, x, n);
}

// A receiver whose size is not small against its distance to the nearest emitter that
// lights it sees F_ij vary strongly across it (a reflector a few cm from a lamp in its
// housing): it takes (size / distance)^2 times the points, at most this many times (a row's
// scaled by its area share: RowNearFieldFactor). Far receivers (every one in the Cornell box)
// keep the points asked for.
constexpr double kMaxNearFieldFactor = 16;

int NearFieldFactor(double radius, double distance) {
  if (!std::isfinite(distance)) return 1;
  const double ratio = 2 * radius / std::max(distance, 1e-300);
  return static_cast<int>(std::clamp(std::ceil(ratio * ratio), 1.0, kMaxNearFieldFactor));
}

// NearFieldFactor of a set of patches (`members`; empty: the single patch `first`): a patch's
// size about its centroid against the nearest emitter's distance from there; a set's (the
// members' vertices about the area-weighted centroid, seen along the area-weighted normal),
// at one distance query per set.
int SetNearFieldFactor(const PatchMesh& mesh, uint32_t first, std::span<const uint32_t> members,
                       const LightTree& tree) {
  Vec3 centroid = mesh.patches[first].centroid, normal = mesh.patches[first].normal;
  if (!members.empty()) {
    Vec3 weighted, summed;
    double area = 0;
    for (uint32_t p : members) {
      weighted += mesh.patches[p].centroid * mesh.patches[p].area;
      summed += mesh.patches[p].normal * mesh.patches[p].area;
      area += mesh.patches[p].area;
    }
    if (area > 0 && Length(summed) > 0) centroid = weighted / area, normal = Normalize(summed);
  }
  double radius = 0;
  const auto widen = [&](uint32_t p) {
    const Patch& patch = mesh.patches[p];
    for (int k = 0; k < patch.VertexCount(); ++k)
      radius = std::max(radius, Length(mesh.positions[patch.v[k]] - centroid));
  };
  if (members.empty()) widen(first);
  for (uint32_t p : members) widen(p);
  return NearFieldFactor(radius, tree.NearestDistance(centroid, normal));
}

}  // namespace

std::vector<EmitterShape> EmitterShapes(const RowContext& context) {
  std::vector<EmitterShape> shapes;
  for (uint32_t j = 0; j < context.emitter.size(); ++j) {
    if (!context.emitter[j]) continue;
    const double exitance = j < context.emission.size() ? context.emission[j] : 1.0;
    // An emitting unknown is one patch (grouping never groups emitters); the shape names
    // the unknown, its column.
    shapes.push_back(MakeEmitterShape(*context.mesh, context.FirstPatch(j), exitance));
    shapes.back().patch = j;
  }
  return shapes;
}

LightSampler::LightSampler(const RowContext& context, const LightSampler* near_field)
    : context_(context),
      tree_(EmitterShapes(context)),
      near_field_(near_field != nullptr ? near_field->tree_ : tree_),
      tree_index_(context.emitter.size(), 0) {
  uint32_t k = 0;  // EmitterShapes' order
  for (uint32_t j = 0; j < context.emitter.size(); ++j) {
    if (context.emitter[j]) tree_index_[j] = k++;
  }
}

uint64_t LightSampler::AddEmitterColumns(uint32_t i, int points, int per_point, uint64_t seed,
                                         RowAccumulator& row, std::span<const CosineHit> hits,
                                         uint32_t cosine_rays, double area_share) const {
  if (tree_.empty() || points < 1 || per_point < 1) return 0;
  const std::span<const uint32_t> members =
      context_.SinglePatch(i) ? std::span<const uint32_t>() : context_.clusters->Members(i);
  points *= RowNearFieldFactor(
      SetNearFieldFactor(*context_.mesh, context_.FirstPatch(i), members, near_field_), area_share);
  const double samples = static_cast<double>(points) * per_point;
  for (const CosineHit& hit : hits) {
    row.Add(hit.emitter, CosineHitValue(hit, cosine_rays, samples));
  }
  return AddSamples(UnknownPointSampler(*context_.mesh, context_.clusters, i), i, points, per_point,
                    seed, i, cosine_rays / samples,
                    [&row](uint32_t j, double v) { row.Add(j, v); });
}

double LightSampler::CosineHitValue(const CosineHit& hit, double k, double n) const {
  const uint32_t emitter = tree_index_[hit.emitter];
  const uint32_t node = tree_.Sampled(emitter);
  const double form_factor = RejectionFormFactor(tree_.Shape(node), hit.x, hit.n);
  if (!(form_factor >= kRejectionFormFactor)) return 0;
  const double probability = tree_.Probability(tree_.CutAt(hit.x, hit.n), hit.x, hit.n, emitter);
  return form_factor / (k * form_factor + n * probability);
}

uint64_t LightSampler::CellEmitterColumns(uint32_t c, int budget, uint64_t seed,
                                          std::vector<CellColumn>& columns) const {
  columns.clear();
  if (tree_.empty() || budget < 1) return 0;
  const std::span<const uint32_t> members = context_.cells->Members(c);
  const uint32_t receiver = context_.UnknownOf(members[0]);
  const int cells = static_cast<int>(context_.CellsOf(receiver).size());
  const int samples = (budget + cells - 1) / std::max(cells, 1);
  const int per_point = CellSamplesAtAPoint(samples, members.size());
  const int points =
      (samples + per_point - 1) / per_point *
      SetNearFieldFactor(*context_.mesh, members[0],
                         members.size() > 1 ? members : std::span<const uint32_t>(), tree_);
  return AddSamples(
      UnknownPointSampler(*context_.mesh, context_.cells, c), receiver, points, per_point,
      seed ^ kCellSeed, c, 0, [&columns](uint32_t j, double v) { AddCellColumn(columns, j, v); },
      /*choices_across_set=*/true);
}

uint64_t LightSampler::AddGroupEmitterColumns(uint32_t g, int budget, uint64_t seed,
                                              RowAccumulator& row) const {
  thread_local std::vector<CellColumn> columns;
  uint64_t rays = 0;
  for (uint32_t c : context_.CellsOf(g)) {
    rays += CellEmitterColumns(c, budget, seed, columns);
    const double weight = context_.cells->area[c] / context_.Area(g);
    for (const CellColumn& column : columns) row.Add(column.emitter, weight * column.form_factor);
    if (context_.cell_columns != nullptr) context_.cell_columns->Keep(c, seed, budget, columns);
  }
  return rays;
}

template <typename AddFn>
uint64_t LightSampler::AddSamples(const UnknownPointSampler& sample_point, uint32_t receiver,
                                  int points, int per_point, uint64_t seed, uint64_t index,
                                  double cosine_share, const AddFn& add,
                                  bool choices_across_set) const {
  const size_t count = static_cast<size_t>(points) * static_cast<size_t>(per_point);
  // Per-thread scratch, reused row to row.
  thread_local std::vector<Point2> on_patch, directions;
  thread_local std::vector<StreamRay> rays;
  thread_local std::vector<PendingSample> pending;
  on_patch.resize(static_cast<size_t>(points));
  directions.resize(count);
  rays.clear();
  pending.clear();
  ShiftedMultiJitteredSamples(PatternSeed(seed, index, kLightPointStream), kLightPointStream,
                              on_patch);
  // The directions of a point's samples are a multi-jittered set of their own (stratified
  // over the emitter, or the tiled rectangle, they mostly share); samples of one point each
  // take theirs from one set over all points.
  const uint32_t direction_pattern = PatternSeed(seed, index, kLightDirectionStream);
  if (per_point == 1) {
    ShiftedMultiJitteredSamples(direction_pattern, kLightDirectionStream, directions);
  }
  for (size_t p = 0; p < on_patch.size(); ++p) {
    const uint32_t first = static_cast<uint32_t>(p) * static_cast<uint32_t>(per_point);
    if (per_point > 1) {
      ShiftedMultiJitteredSamples(PatternSeed(direction_pattern, p), kLightDirectionStream,
                                  std::span<Point2>(directions).subspan(first, per_point));
    }
    const SurfacePoint at = sample_point(on_patch[p]);
    SamplePoint(at.x, at.n, receiver, seed, index, first,
                std::span<const Point2>(directions).subspan(first, per_point), rays, pending,
                cosine_share,
                per_point == 1 || choices_across_set ? static_cast<uint32_t>(count) : 0);
  }
  context_.caster->OccludedStream(rays);
  for (size_t r = 0; r < rays.size(); ++r) {
    if (!rays[r].Occluded()) {
      add(pending[r].emitter, pending[r].form_factor / static_cast<double>(count));
    }
  }
  return rays.size();
}

void LightSampler::SamplePoint(const Vec3& x, const Vec3& n, uint32_t receiver, uint64_t seed,
                               uint64_t index, uint32_t first, std::span<const Point2> directions,
                               std::vector<StreamRay>& rays, std::vector<PendingSample>& pending,
                               double cosine_share, uint32_t strata) const {
  if (tree_.empty()) return;
  const uint32_t per_point = static_cast<uint32_t>(directions.size());
  const uint32_t choice_pattern = PatternSeed(seed, index, kLightChoiceStream);
  const uint32_t rejection_pattern = PatternSeed(seed, index, kRejectionStream);
  const Frame frame = Frame::FromNormal(n);
  const LightTree::Cut cut = tree_.CutAt(x, n);
  const bool one_choice = tree_.OneChoice(cut);  // no u to draw
  // The point's solid-angle samplers, set up once per sampled node (an emitter or a tiled
  // rectangle) its samples choose: per-thread scratch (kilobytes that a fresh array would
  // clear at every point), the first sampler_count of them the point's.
  thread_local std::array<std::optional<EmitterPointSampler>, kLightSamplesAtAPoint> samplers;
  std::array<uint32_t, kLightSamplesAtAPoint> sampler_node;
  size_t sampler_count = 0;
  const auto sampler_of = [&](uint32_t node) -> const EmitterPointSampler& {
    for (size_t m = 0; m < sampler_count; ++m) {
      if (sampler_node[m] == node) return *samplers[m];
    }
    const size_t m = sampler_count < samplers.size() ? sampler_count++ : samplers.size() - 1;
    sampler_node[m] = node;
    return samplers[m].emplace(tree_.Shape(node), x, n);
  };
  for (uint32_t k = 0; k < per_point; ++k) {
    // One stratum of [0, 1) per sample of the point (with `strata`: per sample of the set),
    // in a permuted order, jittered.
    const uint32_t s = first + k;
    const uint32_t count = strata > 0 ? strata : per_point;
    const uint32_t stratum = one_choice   ? 0
                             : strata > 0 ? PermuteIndex(s, strata, choice_pattern)
                                          : PermuteIndex(k, per_point, choice_pattern + s);
    const double u = one_choice ? 0.5 : (stratum + RandomFloat(s, choice_pattern)) / count;
    const auto choice = tree_.Choose(cut, x, n, std::min(u, 0x1.fffffffffffffp-1));
    if (!choice) continue;
    const EmitterShape& shape = tree_.Shape(choice->node);
    if (tree_.IsLeaf(choice->node) && shape.patch == receiver) continue;
    // The exact unoccluded form factor where the cut has it or the choice of the direction's
    // sampling needs it; else (-1) only its bound, below kRejectionFormFactor.
    double form_factor = choice->form_factor;
    if (form_factor < 0) form_factor = RejectionFormFactor(shape, x, n);
    if (form_factor == 0) continue;
    Vec3 target;
    double value;  // the sample's F_j(x) estimate, if its ray is unoccluded
    if (form_factor >= kRejectionFormFactor) {
      if (!CosineDirectionOnEmitter(shape, x, frame, PatternSeed(rejection_pattern, s), target)) {
        continue;
      }
      // F / P, or its balance-heuristic share beside the row's cosine rays (per light sample,
      // times N): F / (P + (k / N) F).
      value = form_factor / (choice->probability + cosine_share * form_factor);
    } else {
      const EmitterSample sample = sampler_of(choice->node)(directions[k]);
      if (!(sample.pdf > 0)) continue;
      const Vec3 d = sample.point - x;
      const double cos_x = Dot(n, d) / Length(d);
      if (!(cos_x > 0)) continue;
      target = sample.point;
      value = cos_x / (std::numbers::pi * sample.pdf * choice->probability);
    }
    // The emitter the point lies on (a tiled rectangle's are its patches).
    const std::optional<uint32_t> lit = tree_.Locate(choice->node, target);
    if (!lit) continue;
    const EmitterShape& emitter = tree_.Emitter(*lit);
    if (emitter.patch == receiver) continue;
    rays.push_back(StreamRay::Segment(x + n * context_.ray_epsilon,
                                      target + emitter.normal * context_.ray_epsilon));
    // Only the emitter's opaque part emits: a cosine ray meets it with that probability.
    pending.push_back({emitter.patch, value * emitter.opacity});
  }
}

}  // namespace radflux
