// MGF colours and their conversion to radflux's linear RGB bands.
//
// An MGF colour is a CIE 1931 (x, y) chromaticity only; the amount comes from the material
// value that uses it (`rd` reflectance, `ed` emittance in lm/m^2), which is the luminance
// component Y. Spectra (`cspec`) and black bodies (`cct`) are reduced to (x, y) with the CIE
// 1931 2-degree colour-matching functions sampled every 10 nm from 380 to 780 nm, as the MGF
// parser does.
//
// RGB: linear, Rec. 709 / sRGB primaries (R 0.64,0.33; G 0.30,0.60; B 0.15,0.06) with the
// equal-energy white E (x = y = 1/3) as the white point, i.e. the RGB that Radiance and
// RenderPark use for MGF. So the MGF neutral colour (the default, x = y = 1/3) with value Y
// becomes (Y, Y, Y) exactly; with D65 as white every MGF "white" would turn pink.
// Chromaticities outside that RGB gamut give negative components (see mgf_material.h).
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"

namespace radflux {

struct MgfColor {
  double x = 1.0 / 3.0;  // CIE 1931 chromaticity x
  double y = 1.0 / 3.0;  // CIE 1931 chromaticity y

  bool operator==(const MgfColor&) const = default;
};

// Luminous efficacy used to turn MGF lumens into radflux watts: 179 lm/W, Radiance's
// WHTEFFICACY for equal-energy white. So `ed` lm/m^2 is emission E = ed / 179 W/m^2.
inline constexpr double kMgfLumensPerWatt = 179.0;

// (x, y) of the spectrum `samples` spaced evenly from `wl_min` to `wl_max` nm (cspec).
// Error (no location) if the range is empty, there are fewer than two samples or the
// spectrum's X + Y + Z is not positive between 380 and 780 nm. (Negative samples are allowed,
// as in MGF: the phosphor curves of Materials/illums.mgf have some.)
absl::StatusOr<MgfColor> SpectrumChromaticity(double wl_min, double wl_max,
                                              const std::vector<double>& samples);

// (x, y) of a black body at `kelvin` (cct). Error below 1000 K, as in MGF.
absl::StatusOr<MgfColor> BlackbodyChromaticity(double kelvin);

// MGF `cmix`: colours mixed with luminance weights (each weight is the Y it contributes).
// Weights must be >= 0 with a positive sum.
MgfColor MixColors(const std::vector<double>& weights, const std::vector<MgfColor>& colors);

// Linear RGB (see above) of chromaticity `c` with luminance `luminance_y`. Components may be
// negative for colours outside the RGB gamut.
Rgb XyYToLinearRgb(const MgfColor& c, double luminance_y);

// The inverse: chromaticity and luminance of a linear RGB colour (for tests and tools).
// Precondition: X + Y + Z of `rgb` is not 0.
MgfColor LinearRgbToXyY(const Rgb& rgb, double* luminance_y);

}  // namespace radflux
