// analytic: for every patch j that can exchange light with i, Lambert's exact
// point-to-polygon form factor at s stratified points on i, times visibility from
// one shadow ray per point. O(n) pairs and up to n*s rays per row: the reference. The
// contour integrals of a row share the terms of the edges its patches share.
#include <numeric>
#include <vector>

#include "solver/formfactor/analytic_pair.h"
#include "solver/formfactor/builders.h"

namespace radflux {
namespace {

class AnalyticBuilder final : public RowBuilder {
 public:
  AnalyticBuilder(const RowContext& context, const FormFactorOptions& options)
      : context_(context),
        options_(options),
        pairs_(context),
        columns_(context.mesh->size()),
        edges_(*context.mesh) {
    std::iota(columns_.begin(), columns_.end(), 0u);
  }

  uint64_t BuildRow(uint32_t i, RowAccumulator& row) const override {
    const PatchMesh& mesh = *context_.mesh;
    const std::vector<Vec3> points = PatchSamplePoints(mesh, i, options_.samples, options_.seed);
    // The cache holds one term per (edge, point): ~16 bytes each, per thread. Beyond
    // kMaxCachedTerms (32 MiB) the terms are computed per patch instead.
    constexpr size_t kMaxCachedTerms = size_t{1} << 21;
    if (edges_.size() * points.size() > kMaxCachedTerms) {
      return pairs_.AddColumns(i, columns_, points, options_.seed, row);
    }
    thread_local ContourCache contours;  // per-thread scratch, begun row by row
    contours.Begin(pairs_.Patches(), edges_, points, mesh.patches[i].normal);
    return pairs_.AddColumns(i, columns_, points, options_.seed, row, &contours);
  }

 private:
  const RowContext& context_;
  FormFactorOptions options_;
  AnalyticPairs pairs_;
  std::vector<uint32_t> columns_;  // every patch
  PatchEdges edges_;
};

}  // namespace

std::unique_ptr<RowBuilder> MakeAnalyticBuilder(const RowContext& context,
                                                const FormFactorOptions& options) {
  return std::make_unique<AnalyticBuilder>(context, options);
}

}  // namespace radflux
