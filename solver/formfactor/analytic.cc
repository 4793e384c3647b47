// analytic: for every patch j that can exchange light with i, Lambert's exact
// point-to-polygon form factor at s stratified points on i, times visibility from
// one shadow ray per point. O(n) pairs and up to n*s rays per row: the reference.
#include <numeric>
#include <vector>

#include "solver/formfactor/analytic_pair.h"
#include "solver/formfactor/builders.h"

namespace radflux {
namespace {

class AnalyticBuilder final : public RowBuilder {
 public:
  AnalyticBuilder(const RowContext& context, const FormFactorOptions& options)
      : context_(context), options_(options), columns_(context.mesh->size()) {
    std::iota(columns_.begin(), columns_.end(), 0u);
  }

  uint64_t BuildRow(uint32_t i, RowAccumulator& row) const override {
    return AddAnalyticColumns(context_, i, columns_, options_.samples, options_.seed, row);
  }

 private:
  const RowContext& context_;
  FormFactorOptions options_;
  std::vector<uint32_t> columns_;  // every patch
};

}  // namespace

std::unique_ptr<RowBuilder> MakeAnalyticBuilder(const RowContext& context,
                                                const FormFactorOptions& options) {
  return std::make_unique<AnalyticBuilder>(context, options);
}

}  // namespace radflux
