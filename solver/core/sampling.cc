#include "solver/core/sampling.h"

#include <algorithm>
#include <array>
#include <bit>
#include <map>
#include <utility>
#include <vector>

namespace radflux {
namespace {

bool IsPowerOfTwo(uint32_t l) { return (l & (l - 1)) == 0; }

// i % l and i / l with a mask and a shift when l is a power of two (the common sample
// counts: 1, 4, 16, 64, ...), where the hardware division is most of the cost.
uint32_t Mod(uint32_t i, uint32_t l) { return IsPowerOfTwo(l) ? i & (l - 1) : i % l; }
uint32_t Div(uint32_t i, uint32_t l) { return IsPowerOfTwo(l) ? i >> std::countr_zero(l) : i / l; }

// x / l, bit for bit: a multiplication by the exact 2^-k when l = 2^k.
double DivideBy(double x, uint32_t l) {
  if (!IsPowerOfTwo(l)) return x / l;
  return x * std::bit_cast<double>(uint64_t{1023u - std::countr_zero(l)} << 52);
}

}  // namespace

uint32_t PermuteIndex(uint32_t i, uint32_t l, uint32_t p) {
  if (l == 1) return 0;  // the only index (a single sample, or one stratum per axis)
  uint32_t w = l - 1;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  do {
    i ^= p;
    i *= 0xe170893d;
    i ^= p >> 16;
    i ^= (i & w) >> 4;
    i ^= p >> 8;
    i *= 0x0929eb3f;
    i ^= p >> 23;
    i ^= (i & w) >> 1;
    i *= 1 | p >> 27;
    i *= 0x6935fa69;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3;
    i ^= (i & w) >> 2;
    i *= 0xc860a3df;
    i &= w;
    i ^= i >> 5;
  } while (i >= l);
  return Mod(i + p, l);
}

double RandomFloat(uint32_t i, uint32_t p) {
  i ^= p;
  i ^= i >> 17;
  i ^= i >> 10;
  i *= 0xb36534e5;
  i ^= i >> 12;
  i ^= i >> 21;
  i *= 0x93fc4795;
  i ^= 0xdf6e307f;
  i ^= i >> 17;
  i *= 1 | p >> 18;
  return i * (1.0 / 4294967808.0);
}

namespace {

constexpr uint32_t kStratumX = 0xa511e9b3, kStratumY = 0x63d83595;
constexpr uint32_t kJitterX = 0xa399d265, kJitterY = 0x711ad6a5;

// The strata of n multi-jittered samples: m x cols >= n cells, of which n are taken.
struct Strata {
  explicit Strata(uint32_t n)
      : m(std::max<uint32_t>(1, static_cast<uint32_t>(std::sqrt(double(n))))),
        cols(Div(n + m - 1, m)),
        cells(m * cols) {}
  uint32_t m, cols, cells;
};

// Sample i of pattern p, given the permutations within the strata: stratum_x(k) =
// PermuteIndex(k, m, p * kStratumX) for k < m, stratum_y(k) = PermuteIndex(k, cols, ...).
template <class StratumX, class StratumY>
Point2 PlaceSample(const Strata& g, uint32_t i, uint32_t p, StratumX stratum_x,
                   StratumY stratum_y) {
  const uint32_t s = PermuteIndex(i, g.cells, p * 0x51633e2d);
  const uint32_t s_mod_m = Mod(s, g.m), s_div_m = Div(s, g.m);
  const uint32_t sx = stratum_x(s_mod_m);
  const uint32_t sy = stratum_y(s_div_m);
  const double jx = RandomFloat(s, p * kJitterX);
  const double jy = RandomFloat(s, p * kJitterY);
  return {std::min(DivideBy(s_mod_m + DivideBy(sy + jx, g.cols), g.m), 0x1.fffffffffffffp-1),
          std::min(DivideBy(s_div_m + DivideBy(sx + jy, g.m), g.cols), 0x1.fffffffffffffp-1)};
}

}  // namespace

Point2 MultiJitteredSample(uint32_t i, uint32_t n, uint32_t p) {
  const Strata g(n);
  return PlaceSample(
      g, i, p, [&](uint32_t k) { return PermuteIndex(k, g.m, p * kStratumX); },
      [&](uint32_t k) { return PermuteIndex(k, g.cols, p * kStratumY); });
}

void MultiJitteredSamples(uint32_t p, std::span<Point2> out) {
  const uint32_t n = static_cast<uint32_t>(out.size());
  if (n == 1) {  // one stratum, index 0: PlaceSample's divisions by 1 leave the jitter alone
    out[0] = {RandomFloat(0, p * kJitterX), RandomFloat(0, p * kJitterY)};
    return;
  }
  const Strata g(n);
  constexpr uint32_t kMaxStrata = 64;
  if (g.cols > kMaxStrata) {  // n > 4,000 or so: one sample at a time
    for (uint32_t i = 0; i < n; ++i) out[i] = MultiJitteredSample(i, n, p);
    return;
  }
  std::array<uint32_t, kMaxStrata> stratum_x, stratum_y;
  for (uint32_t k = 0; k < g.m; ++k) stratum_x[k] = PermuteIndex(k, g.m, p * kStratumX);
  for (uint32_t k = 0; k < g.cols; ++k) stratum_y[k] = PermuteIndex(k, g.cols, p * kStratumY);
  for (uint32_t i = 0; i < n; ++i) {
    out[i] = PlaceSample(
        g, i, p, [&](uint32_t k) { return stratum_x[k]; },
        [&](uint32_t k) { return stratum_y[k]; });
  }
}

void ShiftedMultiJitteredSamples(uint32_t p, uint64_t stream, std::span<Point2> out) {
  constexpr uint64_t kSharedSetSeed = 0x51ed270bu;
  constexpr size_t kLargestShared = 256;  // larger sets are drawn whole each time
  const size_t n = out.size();
  if (n > kLargestShared) return MultiJitteredSamples(p, out);
  thread_local std::map<std::pair<uint64_t, size_t>, std::vector<Point2>> shared;
  std::vector<Point2>& set = shared[{stream, n}];
  if (set.size() != n) {
    set.resize(n);
    MultiJitteredSamples(PatternSeed(kSharedSetSeed, n, stream), set);
  }
  const Point2 shift = RandomShift(p);
  for (size_t i = 0; i < n; ++i) out[i] = CranleyPattersonShift(set[i], shift);
}

namespace {
Point2 InvertUniformDiskConcentric(Point2 p) {
  const double theta = std::atan2(p.y, p.x);  // [-pi, pi]
  const double r = std::sqrt(p.x * p.x + p.y * p.y);
  const double pi = std::numbers::pi;
  double ox, oy;
  if (std::abs(theta) < pi / 4 || std::abs(theta) > 3 * pi / 4) {
    ox = r * (std::abs(theta) < pi / 4 ? 1 : -1);
    const double t = std::abs(theta) < pi / 4 ? theta : (theta > 0 ? theta - pi : theta + pi);
    oy = ox * t / (pi / 4);
  } else {
    oy = r * (theta > 0 ? 1 : -1);
    const double t = theta > 0 ? theta : theta + pi;  // in (pi/4, 3pi/4)
    ox = oy * (pi / 2 - t) / (pi / 4);
  }
  return {(ox + 1) / 2, (oy + 1) / 2};
}
}  // namespace

Point2 InvertCosineHemisphereSample(const Vec3& w) {
  return InvertUniformDiskConcentric({w.x, w.y});
}

Point2 InvertUniformTriangleSample(double b0, double b1) {
  if (b0 >= b1) return {b0 + b1, 2 * b1};  // the u.x >= u.y branch
  return {2 * b0, b1 + b0};
}

double SampleLinear(double u, double a, double b) {
  if (u == 0 && a == 0) return 0;
  // The root of the CDF (a (2x - x^2) + b x^2) / (a + b) = u, in the form without
  // cancellation when a and b are close.
  const double x = u * (a + b) / (a + std::sqrt((1 - u) * a * a + u * b * b));
  return std::min(x, 0x1.fffffffffffffp-1);
}

double LinearPdf(double x, double a, double b) {
  if (x < 0 || x > 1) return 0;
  return 2 * ((1 - x) * a + x * b) / (a + b);
}

double InvertLinearSample(double x, double a, double b) {
  return x * (a * (2 - x) + b * x) / (a + b);
}

Point2 SampleBilinear(Point2 u, const std::array<double, 4>& w) {
  const double y = SampleLinear(u.y, w[0] + w[1], w[2] + w[3]);
  const double x = SampleLinear(u.x, (1 - y) * w[0] + y * w[2], (1 - y) * w[1] + y * w[3]);
  return {x, y};
}

double BilinearPdf(Point2 p, const std::array<double, 4>& w) {
  if (p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1) return 0;
  const double sum = w[0] + w[1] + w[2] + w[3];
  return 4 *
         ((1 - p.x) * (1 - p.y) * w[0] + p.x * (1 - p.y) * w[1] + (1 - p.x) * p.y * w[2] +
          p.x * p.y * w[3]) /
         sum;
}

Point2 InvertBilinearSample(Point2 p, const std::array<double, 4>& w) {
  return {InvertLinearSample(p.x, (1 - p.y) * w[0] + p.y * w[2], (1 - p.y) * w[1] + p.y * w[3]),
          InvertLinearSample(p.y, w[0] + w[1], w[2] + w[3])};
}

}  // namespace radflux
