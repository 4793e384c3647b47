// Tone mapping: how radiance (W/m^2/sr, i.e. B/pi) becomes a display value. One mapping
// is shared by the PNG, the PLY colours and the glTF COLOR_0 so they all look alike:
//   linear = clamp(radiance * scale * 2^exposure_stops, 0, 1), then sRGB encoding for 8 bits.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/core/bands.h"

namespace radflux {

struct ToneMapOptions {
  double scale = 1.0;           // multiplier on radiance; radiance 1/scale W/m^2/sr is white
  double exposure_stops = 0.0;  // further multiplier 2^exposure_stops (photographic stops)
  bool srgb = true;             // 8-bit outputs apply the sRGB transfer curve (off: linear bytes)
};

// Display value in [0, 1], linear light (what glTF COLOR_0 expects).
double ToneMapLinear(double radiance, const ToneMapOptions& options);

// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
double SrgbEncode(double linear);

// 8-bit display value: ToneMapLinear, then SrgbEncode when options.srgb, rounded.
uint8_t ToneMapByte(double radiance, const ToneMapOptions& options);
std::array<uint8_t, 3> ToneMapBytes(const Rgb& radiance, const ToneMapOptions& options);

// A scale that maps the given percentile (in [0, 1]) of the largest band of the non-zero
// `radiance` values to white; 1 when every value is zero. Deterministic.
double AutoExposureScale(const std::vector<Rgb>& radiance, double percentile = 0.95);

}  // namespace radflux
