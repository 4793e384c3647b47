// analytic: for every patch j that can exchange light with i, Lambert's exact
// point-to-polygon form factor at s stratified points on i, times visibility from
// one shadow ray per point. O(n) pairs and up to n*s rays per row: the reference.
#include <vector>

#include "solver/formfactor/analytic_pair.h"
#include "solver/formfactor/builders.h"

namespace radflux {
namespace {

class AnalyticBuilder final : public RowBuilder {
 public:
  AnalyticBuilder(const RowContext& context, const FormFactorOptions& options)
      : context_(context), options_(options) {}

  uint64_t BuildRow(uint32_t i, RowAccumulator& row) const override {
    const PatchMesh& mesh = *context_.mesh;
    const std::vector<Vec3> points = PatchSamplePoints(mesh, i, options_.samples, options_.seed);
    uint64_t rays = 0;
    for (uint32_t j = 0; j < mesh.size(); ++j) {
      if (!PatchesCanExchange(mesh, i, j)) continue;
      row.Add(j, AnalyticPairFormFactor(context_, i, points, j, options_.seed, rays));
    }
    return rays;
  }

 private:
  const RowContext& context_;
  FormFactorOptions options_;
};

}  // namespace

std::unique_ptr<RowBuilder> MakeAnalyticBuilder(const RowContext& context,
                                                const FormFactorOptions& options) {
  return std::make_unique<AnalyticBuilder>(context, options);
}

}  // namespace radflux
