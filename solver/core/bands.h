// Colour bands: radflux solves per band (red, green, blue). A grey scene is solved
// in one band and copied to the others.
#pragma once

#include <array>
#include <cstddef>

namespace radflux {

inline constexpr int kBands = 3;

// A per-band quantity (reflectance, or radiosity / emission in W/m^2 per band).
using Rgb = std::array<double, kBands>;

inline bool IsGrey(const Rgb& c) { return c[0] == c[1] && c[1] == c[2]; }
inline double MeanComponent(const Rgb& c) { return (c[0] + c[1] + c[2]) / kBands; }
inline double MaxComponent(const Rgb& c) {
  double m = c[0];
  for (double v : c) m = v > m ? v : m;
  return m;
}

}  // namespace radflux
