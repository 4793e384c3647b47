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

namespace {

// budget * area / mean_area rounded, within [least, max(least, 4 budget)]; budget (at least
// 1) when mean_area is not a finite number > 0 or the share not a finite number >= 0.
uint32_t InProportion(int budget, double area, double mean_area, int least) {
  const double share = area / mean_area;
  if (!(mean_area > 0 && std::isfinite(mean_area)) || !(share >= 0 && std::isfinite(share))) {
    return static_cast<uint32_t>(std::max(budget, 1));
  }
  const double lo = least, hi = std::max(lo, 4.0 * budget);
  return static_cast<uint32_t>(std::clamp(std::round(budget * share), lo, hi));
}

}  // namespace

uint32_t RowRayCount(int k, double area, double mean_area) {
  return InProportion(k, area, mean_area, std::max({1, k / 4, std::min(k, kLeastRowRays)}));
}


}  // namespace radflux
