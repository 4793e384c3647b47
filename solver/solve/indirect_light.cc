#include "solver/solve/indirect_light.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "solver/sparse/row_store.h"

namespace radflux {

absl::StatusOr<std::vector<Rgb>> ReflectedIndirect(const RadiositySystem& system,
                                                   const std::vector<Rgb>& b) {
  const PatchAttributes& p = *system.patches;
  if (b.size() != p.size()) {
    return absl::InvalidArgumentError(
        absl::StrCat("indirect light: ", b.size(), " radiosities for ", p.size(), " unknowns"));
  }
  std::vector<Rgb> indirect(p.size(), Rgb{});
  const absl::Status read =
      ForEachRows(system.form_factors, system.row_store, [&](const RowsView& rows) {
        for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
          if (MaxComponent(p.reflectance[i]) <= 0) continue;
          Rgb direct{};
          const auto cols = rows.RowCols(i);
          const auto values = rows.RowValues(i);
          for (size_t k = 0; k < cols.size(); ++k) {
            for (int band = 0; band < kBands; ++band)
              direct[band] += values[k] * p.emission[cols[k]][band];
          }
          for (int band = 0; band < kBands; ++band) {
            indirect[i][band] = std::max(
                0.0, b[i][band] - p.emission[i][band] - p.reflectance[i][band] * direct[band]);
          }
        }
      });
  if (!read.ok()) return read;
  return indirect;
}

}  // namespace radflux
