#include "solver/adaptive/adaptive_refine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "solver/core/parallel.h"
#include "solver/core/seconds_since.h"
#include "solver/formfactor/analytic_pair.h"
#include "solver/formfactor/row_builder.h"
#include "solver/formfactor/row_context.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/raytrace/embree_ray_caster.h"

namespace radflux {
namespace {

constexpr uint64_t kLeafPointStream = 21;
constexpr uint64_t kShadowStream = 22;
constexpr uint64_t kContactStream = 23;
using Row = std::vector<std::pair<uint32_t, float>>;

// Sample points of leaf patch i, seeded by its element (so they survive renumbering).
std::vector<Vec3> LeafPoints(const ElementTree& tree, uint32_t node, int s, uint64_t seed) {
  std::vector<Vec3> points;
  const uint32_t pattern = PatternSeed(seed, node, kLeafPointStream);
  for (int m = 0; m < s; ++m) {
    points.push_back(SampleElementPoint(tree.nodes[node], MultiJitteredSample(m, s, pattern)));
  }
  return points;
}

CsrMatrix ToCsr(const std::vector<Row>& rows) {
  CsrMatrix m;
  m.rows = m.cols = static_cast<uint32_t>(rows.size());
  size_t nnz = 0;
  for (const Row& r : rows) nnz += r.size();
  m.Reserve(m.rows, nnz);
  for (const Row& r : rows) {
    for (const auto& [j, v] : r) {
      m.col.push_back(j);
      m.value.push_back(v);
    }
    m.row_begin.push_back(m.col.size());
  }
  return m;
}

struct Pass {
  const ElementTree* tree = nullptr;
  const std::vector<uint32_t>* leaves = nullptr;
  PatchMesh mesh;
  PatchAttributes attributes;
  RowContext context;
};

// Which leaves to split: radiosity jumps to same-face neighbours, shadow boundaries, or
// contact lines.
std::vector<uint8_t> ChooseSplits(const Scene& scene, const ElementTree& tree, const Pass& pass,
                                  const std::vector<Rgb>& b, const AdaptiveOptions& options,
                                  uint64_t seed, int threads, uint64_t& rays) {
  const std::vector<uint32_t>& leaves = *pass.leaves;
  const size_t n = leaves.size();
  std::vector<uint8_t> split(n, 0);
  std::vector<uint32_t> patch_leaf;
  const PatchMesh display = BuildLeafMesh(tree, leaves, true, &patch_leaf);
  std::vector<std::vector<uint32_t>> around(display.positions.size());
  for (uint32_t p = 0; p < display.size(); ++p) {
    for (int k = 0; k < display.patches[p].VertexCount(); ++k) {
      auto& list = around[display.patches[p].v[k]];
      if (std::find(list.begin(), list.end(), patch_leaf[p]) == list.end()) {
        list.push_back(patch_leaf[p]);
      }
    }
  }
  // Jumps of reflected light (B - E: an emitter's own E is flat), measured against the
  // scene's mean: a 20% step in a dark corner moves little light, on the lit floor a lot.
  std::vector<double> reflected(n);
  double b_area = 0, area = 0;
  for (size_t i = 0; i < n; ++i) {
    Rgb r = b[i];
    for (int k = 0; k < kBands; ++k) r[k] -= pass.attributes.emission[i][k];
    reflected[i] = MaxComponent(r);
    b_area += pass.attributes.area[i] * reflected[i];
    area += pass.attributes.area[i];
  }
  const double jump = options.threshold * (area > 0 ? b_area / area : 0);
  // Emitters are not split (unless threshold 0 asks for everything): their own E dominates
  // what they show, and every emitter leaf is a column that each row computes analytically.
  for (const auto& list : around) {
    for (uint32_t x : list) {
      if (pass.context.emitter[x] && options.threshold > 0) continue;
      for (uint32_t y : list) {
        const double bx = reflected[x], by = reflected[y];
        if (std::abs(bx - by) > jump || (options.threshold == 0 && x != y)) {
          split[x] = 1;
        }
      }
    }
  }
  // Shadow boundaries: rays from the leaf to each emitting face, some blocked and some not.
  std::vector<uint32_t> emitters;
  for (uint32_t r : tree.roots) {
    if (scene.materials[scene.faces[tree.nodes[r].face].material].IsEmitter())
      emitters.push_back(r);
  }
  std::vector<uint64_t> block_rays((n + 63) / 64, 0);
  ParallelFor(static_cast<int64_t>(n), 64, threads, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      if (split[i] || !pass.context.needs_row[i] || pass.context.emitter[i]) continue;
      const Element& e = tree.nodes[leaves[i]];
      const int s = options.visibility_rays;
      for (uint32_t r : emitters) {
        const Element& light = tree.nodes[r];
        if (light.face == e.face) continue;
        int blocked = 0, open = 0;
        const uint32_t pattern = PatternSeed(seed ^ leaves[i], r, kShadowStream);
        for (int m = 0; m < s; ++m) {
          const Point2 u = MultiJitteredSample(m, s, pattern);
          const Vec3 x = SampleElementPoint(e, u) + e.normal * pass.context.ray_epsilon;
          const Vec3 y =
              SampleElementPoint(light, {u.y, u.x}) + light.normal * pass.context.ray_epsilon;
          if (Dot(y - x, e.normal) <= 0 || Dot(x - y, light.normal) <= 0) continue;
          ++block_rays[begin / 64];
          (pass.context.caster->Occluded({x, y - x, 0, 1 - 1e-6}) ? blocked : open)++;
        }
        if (blocked > 0 && open > 0) split[i] = 1;
      }
      if (!split[i] && StraddlesContact(e, *pass.context.caster, options.visibility_rays,
                                        PatternSeed(seed ^ leaves[i], 0, kContactStream),
                                        pass.context.ray_epsilon, block_rays[begin / 64])) {
        split[i] = 1;
      }
    }
  });
  for (uint64_t r : block_rays) rays += r;
  return split;
}

// Where a pass's rows come from: analytic pairs computed entry by entry from sample points
// fixed per element (so an unchanged row's entries can be patched when a column splits), or
// any other method's RowBuilder, whose rows are rebuilt whole.
class RowSource {
 public:
  RowSource(const RowContext& context, const FormFactorOptions& ff, const ElementTree& tree,
            const std::vector<uint32_t>& leaves)
      : context_(context), ff_(ff), tree_(tree), leaves_(leaves) {
    if (PerEntry()) {
      pairs_.emplace(context);
    } else {
      builder_ = MakeRowBuilder(context, ff);
      const int threads = ThreadCount(ff.threads);
      scratch_.assign(static_cast<size_t>(threads), RowAccumulator(context.mesh->size()));
    }
  }
  bool PerEntry() const { return ff_.method == FormFactorMethod::kAnalytic; }

  // Row i in full; counts the entries computed and the rays cast.
  void FullRow(uint32_t i, Row& row, uint64_t& entries, uint64_t& rays) const {
    if (PerEntry()) {
      const std::vector<Vec3> points = Points(i);
      for (uint32_t j = 0; j < context_.mesh->size(); ++j) Entry(i, points, j, row, entries, rays);
      return;
    }
    RowAccumulator& acc = scratch_[static_cast<size_t>(ThreadIndex())];
    rays += builder_->BuildRow(i, acc);
    RowBlock block;
    acc.Flush(ff_.cutoff, block, &context_.emitter);
    entries += block.col.size();
    for (size_t k = 0; k < block.col.size(); ++k) row.push_back({block.col[k], block.value[k]});
  }

  // Row i's sample points for Entry (seeded by its element, so they survive renumbering).
  std::vector<Vec3> Points(uint32_t i) const {
    return LeafPoints(tree_, leaves_[i], ff_.samples, ff_.seed);
  }

  // F_ij by analytic pairs from row i's Points (PerEntry only), appended when above the cut-off
  // or in an emitter column.
  void Entry(uint32_t i, const std::vector<Vec3>& points, uint32_t j, Row& row, uint64_t& entries,
             uint64_t& rays) const {
    if (!pairs_->CanExchange(i, j)) return;
    ++entries;
    const double f = pairs_->FormFactor(i, points, j, ff_.seed, rays);
    if (f > 0 && (f >= ff_.cutoff || (j < context_.emitter.size() && context_.emitter[j] != 0))) {
      row.push_back({j, static_cast<float>(f)});
    }
  }

 private:
  const RowContext& context_;
  const FormFactorOptions& ff_;
  const ElementTree& tree_;
  const std::vector<uint32_t>& leaves_;
  std::optional<AnalyticPairs> pairs_;           // PerEntry only
  std::unique_ptr<RowBuilder> builder_;          // otherwise
  mutable std::vector<RowAccumulator> scratch_;  // one per thread
};

}  // namespace

bool StraddlesContact(const Element& e, const RayCaster& caster, int rays, uint32_t pattern,
                      double epsilon, uint64_t& cast) {
  const Frame frame = Frame::FromNormal(e.normal);
  int buried = 0;
  for (int m = 0; m < rays; ++m) {
    const Point2 u = MultiJitteredSample(m, rays, pattern);
    const Vec3 d = frame.ToWorld(SampleCosineHemisphere({u.y, u.x}));
    const Hit hit = caster.Intersect({SampleElementPoint(e, u) + e.normal * epsilon, d});
    ++cast;
    buried += hit.patch != kNoPatch && Dot(hit.normal, d) > 0;
  }
  return buried > 0 && buried < rays;
}

absl::StatusOr<AdaptiveResult> SolveAdaptive(const Scene& scene, const MeshOptions& mesh_options,
                                             const FormFactorOptions& ff,
                                             const SolverOptions& solver,
                                             const AdaptiveOptions& options,
                                             const SolveCallback& callback) {
  absl::StatusOr<PatchMesh> roots = SubdivideScene(scene, mesh_options);
  if (!roots.ok()) return roots.status();
  absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> caster = EmbreeRayCaster::Create(*roots);
  if (!caster.ok()) return caster.status();
  AdaptiveResult result;
  ElementTree& tree = result.tree;
  tree = ElementTree::FromMesh(*roots);
  std::vector<uint32_t> leaves = tree.Leaves();
  std::vector<Row> rows;
  std::vector<Rgb> b;                // per leaf, warm start for the next solve
  std::vector<uint32_t> new_of_old;  // previous leaf -> first new leaf (children consecutive)
  std::vector<uint8_t> was_split;
  for (int pass_index = 0; pass_index <= options.passes; ++pass_index) {
    const auto start = std::chrono::steady_clock::now();
    Pass pass;
    pass.tree = &tree;
    pass.leaves = &leaves;
    pass.mesh = BuildLeafMesh(tree, leaves, false, nullptr);
    pass.attributes = ComputePatchAttributes(scene, pass.mesh);
    pass.context = MakeRowContext(pass.mesh, pass.attributes, **caster);
    const uint32_t n = static_cast<uint32_t>(leaves.size());
    // Which new leaves are new (need a full row) and the old row each unchanged leaf keeps.
    std::vector<int64_t> old_row(n, -1);
    if (pass_index > 0) {
      for (uint32_t o = 0; o < was_split.size(); ++o)
        if (!was_split[o]) old_row[new_of_old[o]] = o;
    }
    // Ray-hit builders need a caster on this pass's leaves (hits name the patch); analytic
    // pairs only cast shadow rays, which the root mesh answers as well.
    std::unique_ptr<EmbreeRayCaster> leaf_caster;
    if (ff.method != FormFactorMethod::kAnalytic) {
      absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> c = EmbreeRayCaster::Create(pass.mesh);
      if (!c.ok()) return c.status();
      leaf_caster = *std::move(c);
      pass.context = MakeRowContext(pass.mesh, pass.attributes, *leaf_caster);
    }
    std::vector<Row> next(n);
    std::vector<uint8_t> recomputed(n, 0);
    std::vector<uint64_t> entries(n, 0), row_rays(n, 0);
    const RowSource source(pass.context, ff, tree, leaves);
    ParallelFor(n, 16, ff.threads, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        if (!pass.context.needs_row[i]) continue;
        const uint32_t row = static_cast<uint32_t>(i);
        if (old_row[i] < 0) {  // a new patch (or the first pass): the whole row
          recomputed[i] = 1;
          source.FullRow(row, next[i], entries[i], row_rays[i]);
          continue;
        }
        const Row& old = rows[old_row[i]];
        const bool points_at_split = std::any_of(
            old.begin(), old.end(), [&](const auto& entry) { return was_split[entry.first]; });
        if (points_at_split && !source.PerEntry()) {  // ray-hit rows cannot be patched
          recomputed[i] = 1;
          source.FullRow(row, next[i], entries[i], row_rays[i]);
          continue;
        }
        const std::vector<Vec3> points = points_at_split ? source.Points(row) : std::vector<Vec3>{};
        for (const auto& [j_old, f] : old) {
          if (!was_split[j_old]) {
            next[i].push_back({new_of_old[j_old], f});
            continue;
          }
          recomputed[i] = 1;
          for (uint32_t c = 0; c < 4; ++c)
            source.Entry(row, points, new_of_old[j_old] + c, next[i], entries[i], row_rays[i]);
        }
      }
    });
    rows = std::move(next);
    AdaptivePass stats;
    stats.patches = n;
    for (uint32_t i = 0; i < n; ++i) {
      stats.rows_recomputed += recomputed[i];
      stats.entries_computed += entries[i];
      result.rays += row_rays[i];
    }
    if (pass_index > 0) stats.split = (n - was_split.size()) / 3;
    result.form_factors = ToCsr(rows);
    SolverOptions warm = solver;
    std::vector<Rgb> previous = b;
    if (pass_index > 0) warm.initial = &previous;
    absl::StatusOr<SolveResult> solved =
        Solve(RadiositySystem{&result.form_factors, &pass.attributes}, warm, callback);
    if (!solved.ok()) return solved.status();
    result.solve.iterations += solved->iterations;
    const int iterations = result.solve.iterations;
    result.solve = *std::move(solved);
    result.solve.iterations = iterations;
    b = result.solve.radiosity;
    if (pass_index > 0) {
      double d2 = 0, b2 = 0;
      for (uint32_t i = 0; i < n; ++i) {
        for (int k = 0; k < kBands; ++k) {
          const double d = b[i][k] - previous[i][k];
          d2 += pass.attributes.area[i] * d * d;
          b2 += pass.attributes.area[i] * b[i][k] * b[i][k];
        }
      }
      stats.change_in_b = b2 > 0 ? std::sqrt(d2 / b2) : 0;
    }
    if (pass_index == options.passes || result.solve.cancelled) {
      stats.seconds = SecondsSince(start);
      result.passes.push_back(stats);
      result.leaf_mesh = std::move(pass.mesh);
      break;
    }
    std::vector<uint8_t> split =
        ChooseSplits(scene, tree, pass, b, options, ff.seed, ff.threads, result.rays);
    int64_t budget = options.max_patches - static_cast<int64_t>(n);
    size_t splits = 0;
    for (uint32_t i = 0; i < n; ++i) {
      if (split[i] &&
          (tree.nodes[leaves[i]].depth >= static_cast<uint32_t>(options.max_depth) || budget < 3)) {
        split[i] = 0;
      }
      if (split[i]) {
        budget -= 3;
        ++splits;
      }
    }
    stats.seconds = SecondsSince(start);
    result.passes.push_back(stats);
    if (splits == 0) {
      result.leaf_mesh = std::move(pass.mesh);
      break;
    }
    for (uint32_t i = 0; i < n; ++i)
      if (split[i]) tree.Split(leaves[i]);
    std::vector<uint32_t> next_leaves = tree.Leaves();
    new_of_old.assign(n, 0);
    std::vector<Rgb> warm_b;
    for (uint32_t i = 0, k = 0; i < n; ++i) {
      new_of_old[i] = k;
      for (uint32_t c = 0; c < (split[i] ? 4u : 1u); ++c, ++k) warm_b.push_back(b[i]);
    }
    b = std::move(warm_b);
    was_split = std::move(split);
    leaves = std::move(next_leaves);
  }
  result.leaves = leaves;
  result.leaf_radiosity = result.solve.radiosity;
  result.mesh = BuildLeafMesh(tree, leaves, true, &result.patch_leaf);
  return result;
}

}  // namespace radflux
