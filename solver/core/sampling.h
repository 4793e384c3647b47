// Sampling functions in pairs with their inverse and pdf (after pbrt-v4), and
// correlated multi-jittered sample patterns (Kensler 2013) seeded per patch, so that
// a patch's samples depend only on (job seed, patch index), never on the thread.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <utility>

#include "solver/core/vec3.h"

namespace radflux {

struct Point2 {
  double x = 0, y = 0;
};

// c ? a : b without a branch (bit masks): the samplers choose between two equally likely
// cases per ray, where a conditional jump would be mispredicted every other time.
inline double Select(bool c, double a, double b) {
  const uint64_t mask = uint64_t{0} - static_cast<uint64_t>(c);
  return std::bit_cast<double>((std::bit_cast<uint64_t>(a) & mask) |
                               (std::bit_cast<uint64_t>(b) & ~mask));
}

// 64-bit mix of (seed, index) into a 32-bit pattern id (splitmix64 finaliser).
inline uint32_t PatternSeed(uint64_t seed, uint64_t index, uint64_t stream = 0) {
  uint64_t z = seed * 0x9E3779B97F4A7C15ull ^ (index + 0x632BE59BD9B4E019ull) ^
               (stream * 0xD1B54A32D192ED03ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return static_cast<uint32_t>(z ^ (z >> 31));
}

// Kensler's hashed permutation of [0, l): a bijection chosen by pattern p.
uint32_t PermuteIndex(uint32_t i, uint32_t l, uint32_t p);
// Kensler's hash of (i, p) to a float in [0, 1).
double RandomFloat(uint32_t i, uint32_t p);

// Sample i of n correlated multi-jittered points in [0,1)^2 with pattern p: every
// prefix-free set of n is stratified in 2D and in each 1D projection.
Point2 MultiJitteredSample(uint32_t i, uint32_t n, uint32_t p);
// All n = out.size() samples of pattern p at once: out[i] = MultiJitteredSample(i, n, p),
// bit for bit, with the permutations within the strata computed once per stratum (about a
// third fewer hashes at n = 4).
void MultiJitteredSamples(uint32_t p, std::span<Point2> out);

// u moved toroidally by `shift` on [0,1)^2 (Cranley-Patterson rotation): applied to a
// shared stratified set with a random shift per use, it keeps the set stratified and
// makes each estimate unbiased, at two additions per sample.
inline Point2 CranleyPattersonShift(Point2 u, Point2 shift) {
  const double x = u.x + shift.x, y = u.y + shift.y;
  return {Select(x >= 1, x - 1, x), Select(y >= 1, y - 1, y)};
}
// The random shift of pattern p (two hashed floats).
inline Point2 RandomShift(uint32_t p, uint32_t first = 0) {
  return {RandomFloat(first, p), RandomFloat(first + 1, p)};
}

namespace internal {
// sin and cos of |a| <= pi/4 by their Taylor series to a^12 (error < 1e-11): the one
// place a ray's cost is dominated by libm otherwise.
inline void SinCosQuarter(double a, double& s, double& c) {
  const double a2 = a * a;
  s = a * (1 + a2 * (-1.0 / 6 +
                     a2 * (1.0 / 120 +
                           a2 * (-1.0 / 5040 + a2 * (1.0 / 362880 + a2 * (-1.0 / 39916800))))));
  c = 1 + a2 * (-0.5 + a2 * (1.0 / 24 +
                             a2 * (-1.0 / 720 +
                                   a2 * (1.0 / 40320 + a2 * (-1.0 / 3628800 + a2 / 479001600)))));
}

// Branch-free (Select): the two wedges of the square are equally likely.
inline Point2 SampleUniformDiskConcentric(Point2 u) {
  const double ox = 2 * u.x - 1, oy = 2 * u.y - 1;
  // |ox| > |oy|: theta = pi/4 * oy/ox; otherwise theta = pi/2 - pi/4 * ox/oy.
  const bool wide = std::abs(ox) > std::abs(oy);
  const double r = Select(wide, ox, oy), q = Select(wide, oy, ox);  // |q| <= |r|; q = 0 if r = 0
  double s, c;
  SinCosQuarter(std::numbers::pi / 4 * (q / Select(r == 0, 1, r)), s, c);
  return {Select(wide, r * c, r * s), Select(wide, r * s, r * c)};
}
}  // namespace internal

// Cosine-weighted direction on the hemisphere around +z (concentric mapping). Inline:
// monte_carlo calls it once per ray.
inline Vec3 SampleCosineHemisphere(Point2 u) {
  const Point2 d = internal::SampleUniformDiskConcentric(u);
  const double z = std::sqrt(std::max(0.0, 1 - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
inline double CosineHemispherePdf(double cos_theta) { return cos_theta * std::numbers::inv_pi; }
// Inverse of SampleCosineHemisphere for a direction with z >= 0.
Point2 InvertCosineHemisphereSample(const Vec3& w);

// Uniform barycentric point (b0, b1) on a triangle; b2 = 1 - b0 - b1 (Heitz's
// low-distortion mapping, which keeps stratification).
inline std::pair<double, double> SampleUniformTriangle(Point2 u) {
  const bool lower = u.x < u.y;  // either side equally likely: Select, not a branch
  const double b0 = Select(lower, u.x / 2, u.x - u.y / 2);
  const double b1 = Select(lower, u.y - u.x / 2, u.y / 2);
  return {b0, b1};
}
Point2 InvertUniformTriangleSample(double b0, double b1);

}  // namespace radflux
