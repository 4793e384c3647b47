#include "solver/output/tone_map.h"

#include <algorithm>
#include <cmath>

namespace radflux {

double ToneMapLinear(double radiance, const ToneMapOptions& options) {
  const double value = radiance * options.scale * std::exp2(options.exposure_stops);
  if (!(value > 0)) return 0;  // also maps NaN to black
  return std::min(value, 1.0);
}

double SrgbEncode(double linear) {
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}

uint8_t ToneMapByte(double radiance, const ToneMapOptions& options) {
  double display = ToneMapLinear(radiance, options);
  if (options.srgb) display = SrgbEncode(display);
  return static_cast<uint8_t>(std::lround(std::clamp(display, 0.0, 1.0) * 255));
}

std::array<uint8_t, 3> ToneMapBytes(const Rgb& radiance, const ToneMapOptions& options) {
  return {ToneMapByte(radiance[0], options), ToneMapByte(radiance[1], options),
          ToneMapByte(radiance[2], options)};
}

double AutoExposureScale(const std::vector<Rgb>& radiance, double percentile) {
  std::vector<double> peaks;
  peaks.reserve(radiance.size());
  for (const Rgb& c : radiance) {
    if (MaxComponent(c) > 0) peaks.push_back(MaxComponent(c));
  }
  if (peaks.empty()) return 1;
  const double q = std::clamp(percentile, 0.0, 1.0);
  const auto k = static_cast<size_t>(std::llround(q * static_cast<double>(peaks.size() - 1)));
  std::nth_element(peaks.begin(), peaks.begin() + static_cast<std::ptrdiff_t>(k), peaks.end());
  return 1 / peaks[k];
}

}  // namespace radflux
