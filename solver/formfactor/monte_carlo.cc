// monte_carlo: k cosine-weighted rays from stratified points on patch i; each ray
// that hits the front of patch j adds 1/k to F_ij. Emitter columns are computed
// analytically instead (their direct light would be the noisiest term) and MC hits
// on emitters are dropped, so the two never double count.
#include <vector>

#include "solver/core/sampling.h"
#include "solver/formfactor/analytic_pair.h"
#include "solver/formfactor/builders.h"

namespace radflux {
namespace {

constexpr uint64_t kPositionStream = 11;
constexpr uint64_t kDirectionStream = 12;

class MonteCarloBuilder final : public RowBuilder {
 public:
  MonteCarloBuilder(const RowContext& context, const FormFactorOptions& options)
      : context_(context), options_(options) {
    for (uint32_t j = 0; j < context.mesh->size(); ++j) {
      if (context.emitter[j]) emitters_.push_back(j);
    }
  }

  uint64_t BuildRow(uint32_t i, RowAccumulator& row) const override {
    const PatchMesh& mesh = *context_.mesh;
    const Patch& patch = mesh.patches[i];
    const Frame frame = Frame::FromNormal(patch.normal);
    const uint32_t k = static_cast<uint32_t>(options_.rays);
    const uint32_t position_pattern = PatternSeed(options_.seed, i, kPositionStream);
    const uint32_t direction_pattern = PatternSeed(options_.seed, i, kDirectionStream);
    const double weight = 1.0 / k;
    for (uint32_t r = 0; r < k; ++r) {
      const Vec3 origin =
          SamplePatchPoint(mesh, i, MultiJitteredSample(r, k, position_pattern)) +
          patch.normal * context_.ray_epsilon;
      // Pair position stratum r with a permuted direction stratum (decorrelated padding).
      const uint32_t d = PermuteIndex(r, k, direction_pattern);
      const Vec3 direction = frame.ToWorld(SampleCosineHemisphere(
          MultiJitteredSample(d, k, direction_pattern ^ 0x9e3779b9u)));
      const Hit hit = context_.caster->Intersect({origin, direction});
      if (hit.patch == kNoPatch || context_.emitter[hit.patch]) continue;
      if (Dot(direction, mesh.patches[hit.patch].normal) >= 0) continue;  // back side: absorbed
      row.Add(hit.patch, weight);
    }
    uint64_t rays = k;
    if (!emitters_.empty()) {
      const std::vector<Vec3> points = PatchSamplePoints(mesh, i, options_.samples, options_.seed);
      for (uint32_t j : emitters_) {
        if (!PatchesCanExchange(mesh, i, j)) continue;
        row.Add(j, AnalyticPairFormFactor(context_, i, points, j, options_.seed, rays));
      }
    }
    return rays;
  }

 private:
  const RowContext& context_;
  FormFactorOptions options_;
  std::vector<uint32_t> emitters_;
};

}  // namespace

std::unique_ptr<RowBuilder> MakeMonteCarloBuilder(const RowContext& context,
                                                  const FormFactorOptions& options) {
  return std::make_unique<MonteCarloBuilder>(context, options);
}

}  // namespace radflux
