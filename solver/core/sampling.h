// Sampling functions in pairs with their inverse and pdf (after pbrt-v4), and
// correlated multi-jittered sample patterns (Kensler 2013) seeded per patch, so that
// a patch's samples depend only on (job seed, patch index), never on the thread.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <utility>

#include "absl/container/inlined_vector.h"
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
inline float Select(bool c, float a, float b) {
  const uint32_t mask = uint32_t{0} - static_cast<uint32_t>(c);
  return std::bit_cast<float>((std::bit_cast<uint32_t>(a) & mask) |
                              (std::bit_cast<uint32_t>(b) & ~mask));
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

// One set of n multi-jittered points per pattern, drawn at once into one buffer that stays
// off the heap up to 64 points in all (a hierarchical link's sets): set k is pattern k's n
// points, as MultiJitteredSamples draws them.
template <size_t Sets>
class MultiJitteredSets {
 public:
  MultiJitteredSets(const std::array<uint32_t, Sets>& patterns, size_t n)
      : n_(n), points_(Sets * n) {
    for (size_t k = 0; k < Sets; ++k)
      MultiJitteredSamples(patterns[k], std::span<Point2>(points_.data() + k * n, n));
  }
  std::span<const Point2> operator[](size_t k) const { return {points_.data() + k * n_, n_}; }

 private:
  size_t n_;
  absl::InlinedVector<Point2, 64> points_;
};

// One coordinate of the rotation below: u + shift wrapped back into [0, 1) for u, shift in
// [0, 1) (in float, u + shift may round up to 1 exactly; then the result is 1). T is
// double or float.
template <class T>
inline T WrapShift(T u, T shift) {
  const T x = u + shift;
  return Select(x >= 1, x - 1, x);
}
// u moved toroidally by `shift` on [0,1)^2 (Cranley-Patterson rotation): applied to a
// shared stratified set with a random shift per use, it keeps the set stratified and
// makes each estimate unbiased, at two additions per sample.
inline Point2 CranleyPattersonShift(Point2 u, Point2 shift) {
  return {WrapShift(u.x, shift.x), WrapShift(u.y, shift.y)};
}
// The random shift of pattern p (two hashed floats).
inline Point2 RandomShift(uint32_t p, uint32_t first = 0) {
  return {RandomFloat(first, p), RandomFloat(first + 1, p)};
}

// n = out.size() points of one fixed multi-jittered set per (n, stream), shifted toroidally
// by pattern p's RandomShift: stratified as MultiJitteredSamples' and unbiased, at two hashes
// a set once each thread has made the fixed set (the per-row light samples drew a fresh set
// of 4 or 16 points per pattern: 7.5% of the Cornell box's instructions in their hashes).
// Dimensions sampled together (a point and its direction) take different streams, or their
// sets of one size would be the same points moved alike.
void ShiftedMultiJitteredSamples(uint32_t p, uint64_t stream, std::span<Point2> out);

namespace internal {
// sin and cos of |a| <= pi/4 by their Taylor series to a^12 (truncation < 1e-11; in
// float the rounding, a few ulp, dominates): the one place a ray's cost is dominated by
// libm otherwise. T is double or float.
template <class T>
inline void SinCosQuarter(T a, T& s, T& c) {
  const T a2 = a * a;
  s = a * (1 + a2 * (T(-1.0 / 6) +
                     a2 * (T(1.0 / 120) + a2 * (T(-1.0 / 5040) + a2 * (T(1.0 / 362880) +
                                                                       a2 * T(-1.0 / 39916800))))));
  c = 1 + a2 * (T(-0.5) +
                a2 * (T(1.0 / 24) +
                      a2 * (T(-1.0 / 720) +
                            a2 * (T(1.0 / 40320) + a2 * (T(-1.0 / 3628800) + a2 / T(479001600))))));
}
}  // namespace internal

// The concentric map of (ux, uy) in [0,1]^2 to the unit disk, lifted to the hemisphere
// around +z: a cosine-weighted direction (x, y, z), unit up to T's rounding. One
// implementation for both precisions: in double it is SampleCosineHemisphere; in float
// (monte_carlo's rays, which Embree takes in float anyway) x, y and z^2 = cos^2 theta
// (uniform on [0, 1] under the cosine pdf) are within 1e-6 of the double map's for the
// same u (tested; z itself, near the rim, within ~3e-4), and it is branch-free (Select:
// the two wedges of the square are equally likely), so a loop of it vectorises.
template <class T>
inline void CosineHemisphereDirection(T ux, T uy, T& x, T& y, T& z) {
  const T ox = 2 * ux - 1, oy = 2 * uy - 1;
  // |ox| > |oy|: theta = pi/4 * oy/ox; otherwise theta = pi/2 - pi/4 * ox/oy.
  const bool wide = std::abs(ox) > std::abs(oy);
  const T r = Select(wide, ox, oy), q = Select(wide, oy, ox);  // |q| <= |r|; q = 0 if r = 0
  T s, c;
  internal::SinCosQuarter(T(std::numbers::pi / 4) * (q / Select(r == 0, T(1), r)), s, c);
  x = Select(wide, r * c, r * s);
  y = Select(wide, r * s, r * c);
  z = std::sqrt(std::max(T(0), 1 - x * x - y * y));
}

// Cosine-weighted direction on the hemisphere around +z (concentric mapping).
inline Vec3 SampleCosineHemisphere(Point2 u) {
  Vec3 w;
  CosineHemisphereDirection(u.x, u.y, w.x, w.y, w.z);
  return w;
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

// x in [0, 1] with density proportional to (1 - x) a + x b (a, b >= 0, not both 0), its pdf
// and inverse.
double SampleLinear(double u, double a, double b);
double LinearPdf(double x, double a, double b);
double InvertLinearSample(double x, double a, double b);

// A point of [0, 1]^2 with density proportional to the bilinear interpolation of the corner
// weights w = {w(0,0), w(1,0), w(0,1), w(1,1)} (>= 0, not all 0): y from its linear marginal,
// then x given y. With its pdf and inverse (pbrt-v4's bilinear warp: composed with a
// solid-angle map it approximates cosine-weighted sampling of a light's solid angle).
Point2 SampleBilinear(Point2 u, const std::array<double, 4>& w);
double BilinearPdf(Point2 p, const std::array<double, 4>& w);
Point2 InvertBilinearSample(Point2 p, const std::array<double, 4>& w);

}  // namespace radflux
