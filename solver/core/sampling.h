// Sampling functions in pairs with their inverse and pdf (after pbrt-v4), and
// correlated multi-jittered sample patterns (Kensler 2013) seeded per patch, so that
// a patch's samples depend only on (job seed, patch index), never on the thread.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include "solver/core/vec3.h"

namespace radflux {

struct Point2 {
  double x = 0, y = 0;
};

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

// Cosine-weighted direction on the hemisphere around +z (concentric mapping).
Vec3 SampleCosineHemisphere(Point2 u);
inline double CosineHemispherePdf(double cos_theta) { return cos_theta * std::numbers::inv_pi; }
// Inverse of SampleCosineHemisphere for a direction with z >= 0.
Point2 InvertCosineHemisphereSample(const Vec3& w);

// Uniform barycentric point (b0, b1) on a triangle; b2 = 1 - b0 - b1.
std::pair<double, double> SampleUniformTriangle(Point2 u);
Point2 InvertUniformTriangleSample(double b0, double b1);

}  // namespace radflux
