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

uint32_t RowRayCount(int k, double area, double mean_area) {
  const double least = std::max({1, k / 4, std::min(k, kLeastRowRays)}), most = 4.0 * k;
  if (!(mean_area > 0)) return static_cast<uint32_t>(std::max(k, 1));
  return static_cast<uint32_t>(std::clamp(std::round(k * area / mean_area), least, most));
}

}  // namespace radflux
