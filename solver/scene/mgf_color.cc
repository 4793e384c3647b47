#include "solver/scene/mgf_color.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "solver/core/vec3.h"
#include "solver/scene/mgf_transform.h"

namespace radflux {
namespace {

constexpr double kCmfMinNm = 380, kCmfStepNm = 10;
constexpr int kCmfSamples = 41;  // 380, 390, ..., 780 nm

// CIE 1931 2-degree standard observer x-bar, y-bar, z-bar every 10 nm from 380 nm.
constexpr std::array<std::array<double, 3>, kCmfSamples> kCmf = {{
    {0.001368, 0.000039, 0.006450}, {0.004243, 0.000120, 0.020050}, {0.014310, 0.000396, 0.067850},
    {0.043510, 0.001210, 0.207400}, {0.134380, 0.004000, 0.645600}, {0.283900, 0.011600, 1.385600},
    {0.348280, 0.023000, 1.747060}, {0.336200, 0.038000, 1.772110}, {0.290800, 0.060000, 1.669200},
    {0.195360, 0.090980, 1.287640}, {0.095640, 0.139020, 0.812950}, {0.032010, 0.208020, 0.465180},
    {0.004900, 0.323000, 0.272000}, {0.009300, 0.503000, 0.158200}, {0.063270, 0.710000, 0.078250},
    {0.165500, 0.862000, 0.042160}, {0.290400, 0.954000, 0.020300}, {0.433450, 0.994950, 0.008750},
    {0.594500, 0.995000, 0.003900}, {0.762100, 0.952000, 0.002100}, {0.916300, 0.870000, 0.001650},
    {1.026300, 0.757000, 0.001100}, {1.062200, 0.631000, 0.000800}, {1.002600, 0.503000, 0.000340},
    {0.854450, 0.381000, 0.000190}, {0.642400, 0.265000, 0.000050}, {0.447900, 0.175000, 0.000020},
    {0.283500, 0.107000, 0.000000}, {0.164900, 0.061000, 0.000000}, {0.087400, 0.032000, 0.000000},
    {0.046770, 0.017000, 0.000000}, {0.022700, 0.008210, 0.000000}, {0.011359, 0.004102, 0.000000},
    {0.005790, 0.002091, 0.000000}, {0.002899, 0.001047, 0.000000}, {0.001440, 0.000520, 0.000000},
    {0.000690, 0.000249, 0.000000}, {0.000332, 0.000120, 0.000000}, {0.000166, 0.000060, 0.000000},
    {0.000083, 0.000030, 0.000000}, {0.000042, 0.000015, 0.000000},
}};

// The colour-matching functions at `nm`, linearly interpolated (0 outside 380-780 nm).
Vec3 CmfAt(double nm) {
  const double u = (nm - kCmfMinNm) / kCmfStepNm;
  if (u < 0 || u > kCmfSamples - 1) return {};
  const int k = std::min(static_cast<int>(u), kCmfSamples - 2);
  const double f = u - k;
  auto at = [&](int i) { return Vec3(kCmf[i][0], kCmf[i][1], kCmf[i][2]); };
  return at(k) * (1 - f) + at(k + 1) * f;
}

absl::StatusOr<MgfColor> ChromaticityOf(const Vec3& xyz, const char* what) {
  const double sum = xyz.x + xyz.y + xyz.z;
  if (!(sum > 0) || !std::isfinite(sum)) {
    return absl::InvalidArgumentError(absl::StrCat(what, " has no energy between 380 and 780 nm"));
  }
  return MgfColor{xyz.x / sum, xyz.y / sum};
}

// XYZ (as a column) of the RGB primaries scaled so that RGB (1,1,1) is white E, XYZ (1,1,1).
Mat3 RgbToXyz() {
  const double prim[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  Mat3 p;
  for (int c = 0; c < 3; ++c) {
    p.m[0][c] = prim[c][0] / prim[c][1];
    p.m[1][c] = 1.0;
    p.m[2][c] = (1.0 - prim[c][0] - prim[c][1]) / prim[c][1];
  }
  const Vec3 scale = p.Inverse() * Vec3(1, 1, 1);
  for (int r = 0; r < 3; ++r) {
    p.m[r][0] *= scale.x;
    p.m[r][1] *= scale.y;
    p.m[r][2] *= scale.z;
  }
  return p;
}

const Mat3& RgbToXyzMatrix() {
  static const Mat3 m = RgbToXyz();
  return m;
}

const Mat3& XyzToRgbMatrix() {
  static const Mat3 m = RgbToXyz().Inverse();
  return m;
}

}  // namespace

absl::StatusOr<MgfColor> SpectrumChromaticity(double wl_min, double wl_max,
                                              const std::vector<double>& samples) {
  if (samples.size() < 2 || !(wl_max > wl_min)) {
    return absl::InvalidArgumentError("cspec needs wl_min < wl_max and at least two samples");
  }
  const double step = (wl_max - wl_min) / static_cast<double>(samples.size() - 1);
  Vec3 xyz;
  if (step < kCmfStepNm) {  // fine spectrum: sum its samples against interpolated CMFs
    for (size_t i = 0; i < samples.size(); ++i) xyz += CmfAt(wl_min + step * i) * samples[i];
  } else {  // coarse spectrum: interpolate it at the CMF wavelengths
    for (int k = 0; k < kCmfSamples; ++k) {
      const double u = (kCmfMinNm + kCmfStepNm * k - wl_min) / step;
      if (u < 0 || u > static_cast<double>(samples.size() - 1)) continue;
      const size_t i = std::min(static_cast<size_t>(u), samples.size() - 2);
      const double f = u - static_cast<double>(i);
      const double s = samples[i] * (1 - f) + samples[i + 1] * f;
      xyz += Vec3(kCmf[k][0], kCmf[k][1], kCmf[k][2]) * s;
    }
  }
  return ChromaticityOf(xyz, "cspec");
}

absl::StatusOr<MgfColor> BlackbodyChromaticity(double kelvin) {
  if (!(kelvin >= 1000) || !std::isfinite(kelvin)) {
    return absl::InvalidArgumentError("cct needs a temperature of at least 1000 K");
  }
  constexpr double kC2 = 1.4388e-2;  // second radiation constant, m K
  Vec3 xyz;
  for (int k = 0; k < kCmfSamples; ++k) {
    const double m = (kCmfMinNm + kCmfStepNm * k) * 1e-9;
    // Planck's law up to a constant factor (which cancels in x and y).
    const double radiance = 1.0 / (std::pow(m * 1e6, 5) * std::expm1(kC2 / (kelvin * m)));
    xyz += Vec3(kCmf[k][0], kCmf[k][1], kCmf[k][2]) * radiance;
  }
  return ChromaticityOf(xyz, "cct");
}

MgfColor MixColors(const std::vector<double>& weights, const std::vector<MgfColor>& colors) {
  // Weight w of luminance Y = w contributes X + Y + Z = w / y, of which x and y are fractions.
  double sum = 0, x = 0, y = 0;
  for (size_t i = 0; i < weights.size() && i < colors.size(); ++i) {
    if (!(colors[i].y > 0)) continue;
    const double total = weights[i] / colors[i].y;
    sum += total;
    x += total * colors[i].x;
    y += total * colors[i].y;
  }
  if (!(sum > 0) || !std::isfinite(sum)) return MgfColor{};
  return {x / sum, y / sum};
}

Rgb XyYToLinearRgb(const MgfColor& c, double luminance_y) {
  if (!(c.y > 0)) return {0, 0, 0};
  const Vec3 xyz(c.x / c.y * luminance_y, luminance_y, (1 - c.x - c.y) / c.y * luminance_y);
  const Vec3 rgb = XyzToRgbMatrix() * xyz;
  return {rgb.x, rgb.y, rgb.z};
}

MgfColor LinearRgbToXyY(const Rgb& rgb, double* luminance_y) {
  const Vec3 xyz = RgbToXyzMatrix() * Vec3(rgb[0], rgb[1], rgb[2]);
  *luminance_y = xyz.y;
  const double sum = xyz.x + xyz.y + xyz.z;
  return {xyz.x / sum, xyz.y / sum};
}

}  // namespace radflux
