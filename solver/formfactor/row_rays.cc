#include "solver/formfactor/row_rays.h"

#include <algorithm>
#include <cmath>

namespace radflux {

double MeanRowArea(std::span<const double> area, std::span<const uint8_t> has_row) {
  double sum = 0;
  size_t rows = 0;
  for (size_t u = 0; u < area.size() && u < has_row.size(); ++u) {
    if (!has_row[u]) continue;
    sum += area[u];
    ++rows;
  }
  return rows > 0 ? sum / static_cast<double>(rows) : 0;
}

double RowAreaShare(double area, double mean_area) {
  const double share = area / mean_area;
  return mean_area > 0 && std::isfinite(mean_area) && share >= 0 && std::isfinite(share) ? share
                                                                                         : 1.0;
}

uint32_t RowRayCount(int k, double area, double mean_area, bool emits) {
  if (emits) return static_cast<uint32_t>(std::max(1, kEmitterRowRays * k));
  const double least = std::max({1, k / 4, std::min(k, kLeastRowRays)});
  return static_cast<uint32_t>(
      std::clamp(std::round(k * RowAreaShare(area, mean_area)), least, std::max(least, 4.0 * k)));
}

int RowNearFieldFactor(int factor, double share) {
  const double most = std::max(factor, 1);
  return static_cast<int>(std::clamp(std::ceil(factor * share), 1.0, most));
}

bool ReadFromHiddenRow(int k, double area_i, bool i_emits, double area_j, double mean_area) {
  return area_j * RowRayCount(k, area_i, mean_area, i_emits) <
         area_i * RowRayCount(k, area_j, mean_area, false);
}

}  // namespace radflux
