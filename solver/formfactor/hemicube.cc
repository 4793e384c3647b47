// hemicube: a ray-cast hemicube at the patch centroid (Cohen & Greenberg 1985).
// The top face has r x r cells, each side r x r/2; one ray through each cell centre
// adds the cell's delta form factor to the patch it hits. Delta form factors are the
// exact point-to-cell form factors, so they sum to 1 and the only error is aliasing.
// Two things keep aliasing in check: each patch turns its hemicube about the normal by
// its own seeded angle (so cell rays do not line up with a regular mesh's edges), and,
// as in monte_carlo, emitter columns are analytic (from the centroid) and cell hits on
// emitters are dropped (a small bright emitter can fall between cell rays).
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "solver/core/sampling.h"
#include "solver/formfactor/analytic_pair.h"
#include "solver/formfactor/builders.h"
#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

struct Cell {
  Vec3 direction;  // local frame, through the cell centre
  double delta_form_factor;
};

// Cells of the unit hemicube around +z: top z=1, sides x=+-1 and y=+-1 with z in [0,1].
std::vector<Cell> MakeHemicubeCells(int r) {
  std::vector<Cell> cells;
  const double step = 2.0 / r;
  const Vec3 origin, up{0, 0, 1};
  auto add = [&](const Vec3& corner, const Vec3& du, const Vec3& dv) {
    const std::vector<Vec3> cell{corner, corner + du, corner + du + dv, corner + dv};
    cells.push_back({corner + (du + dv) * 0.5, PointToPolygonFormFactor(origin, up, cell)});
  };
  for (int a = 0; a < r; ++a) {
    for (int b = 0; b < r; ++b) add({-1 + a * step, -1 + b * step, 1}, {step, 0, 0}, {0, step, 0});
  }
  const int half = r / 2;
  for (int a = 0; a < r; ++a) {
    for (int b = 0; b < half; ++b) {
      const double t = -1 + a * step, z = b * step;
      add({1, t, z}, {0, step, 0}, {0, 0, step});
      add({-1, t, z}, {0, step, 0}, {0, 0, step});
      add({t, 1, z}, {step, 0, 0}, {0, 0, step});
      add({t, -1, z}, {step, 0, 0}, {0, 0, step});
    }
  }
  return cells;
}

class HemicubeBuilder final : public RowBuilder {
 public:
  HemicubeBuilder(const RowContext& context, const FormFactorOptions& options)
      : context_(context),
        cells_(MakeHemicubeCells(options.hemicube_res)),
        emitters_(EmitterPatches(context)),
        samples_(options.samples),
        seed_(options.seed) {
    if (!emitters_.empty()) pairs_.emplace(context);
  }

  uint64_t BuildRow(uint32_t i, RowAccumulator& row) const override {
    const PatchMesh& mesh = *context_.mesh;
    const Patch& patch = mesh.patches[i];
    const Vec3 edge = Normalize(mesh.Vertex(i, 1) - mesh.Vertex(i, 0));
    const double turn = 2 * std::numbers::pi * RandomFloat(0, PatternSeed(seed_, i, kTurnStream));
    const Vec3 s = edge * std::cos(turn) + Cross(patch.normal, edge) * std::sin(turn);
    const Frame frame{s, Cross(patch.normal, s), patch.normal};
    const Vec3 origin = patch.centroid + patch.normal * context_.ray_epsilon;
    thread_local std::vector<StreamRay> stream;  // per-thread scratch, reused row to row
    stream.resize(cells_.size());
    for (size_t c = 0; c < cells_.size(); ++c) {
      stream[c].SetOrigin(origin);
      stream[c].SetDirection(frame.ToWorld(cells_[c].direction));
      stream[c].ResetHit();
    }
    context_.caster->IntersectStream(stream);
    for (size_t c = 0; c < cells_.size(); ++c) {
      const uint32_t j = stream[c].FrontPatch();  // a back side absorbs the ray
      if (j != kNoPatch && !context_.emitter[j]) row.Add(j, cells_[c].delta_form_factor);
    }
    if (emitters_.empty()) return cells_.size();
    // A hemicube is a point method: emitter columns from the centroid too (exact point form
    // factor, s shadow rays to stratified points on the emitter), so rows stay consistent.
    const std::vector<Vec3> centroid(static_cast<size_t>(samples_), patch.centroid);
    return cells_.size() + pairs_->AddColumns(i, emitters_, centroid, seed_, row);
  }

 private:
  static constexpr uint64_t kTurnStream = 21;
  const RowContext& context_;
  std::vector<Cell> cells_;
  std::vector<uint32_t> emitters_;
  std::optional<AnalyticPairs> pairs_;  // the emitter columns, when there are emitters
  int samples_;
  uint64_t seed_;
};

}  // namespace

std::unique_ptr<RowBuilder> MakeHemicubeBuilder(const RowContext& context,
                                                const FormFactorOptions& options) {
  return std::make_unique<HemicubeBuilder>(context, options);
}

}  // namespace radflux
