// Sampling functions against their inverses, and the stratification they promise.
#include "solver/core/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

namespace radflux {
namespace {

TEST(Sampling, CosineHemisphereInvertsAndStaysOnTheHemisphere) {
  for (uint32_t i = 0; i < 256; ++i) {
    const Point2 u = MultiJitteredSample(i, 256, 3);
    const Vec3 w = SampleCosineHemisphere(u);
    EXPECT_NEAR(Length(w), 1, 1e-12);
    EXPECT_GE(w.z, 0);
    const Point2 back = InvertCosineHemisphereSample(w);
    EXPECT_NEAR(back.x, u.x, 1e-9);
    EXPECT_NEAR(back.y, u.y, 1e-9);
  }
  EXPECT_NEAR(CosineHemispherePdf(1), 1 / std::numbers::pi, 1e-15);
}

TEST(Sampling, CosineHemisphereHasTheRightMean) {
  // E[cos theta] under the cosine pdf is 2/3.
  double mean = 0;
  const uint32_t n = 4096;
  for (uint32_t i = 0; i < n; ++i)
    mean += SampleCosineHemisphere(MultiJitteredSample(i, n, 5)).z / n;
  EXPECT_NEAR(mean, 2.0 / 3.0, 1e-3);
}

TEST(Sampling, CosineHemisphereInFloatIsWithin1e6OfDouble) {
  // monte_carlo's rays take the map in float: x, y and z^2 = cos^2 theta (uniform on
  // [0, 1] under the cosine pdf) within 1e-6 of the double map's for the same input, also
  // at the rim (z = 0, where z itself is off by up to ~sqrt(1e-7)) and the square's corners.
  std::vector<Point2> us;
  for (uint32_t i = 0; i < 65536; ++i) us.push_back(MultiJitteredSample(i, 65536, 17));
  for (double a : {0.0, 0.5, 1.0})
    for (double b : {0.0, 0.25, 0.5, 0.999999, 1.0}) us.push_back({a, b}), us.push_back({b, a});
  double worst = 0;
  for (const Point2& u : us) {
    const float ux = static_cast<float>(u.x), uy = static_cast<float>(u.y);
    float x, y, z;
    CosineHemisphereDirection(ux, uy, x, y, z);
    const Vec3 w = SampleCosineHemisphere({ux, uy});  // the same input, in double
    worst = std::max({worst, std::abs(x - w.x), std::abs(y - w.y),
                      std::abs(static_cast<double>(z) * z - w.z * w.z)});
    EXPECT_GE(z, 0);
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(Sampling, UniformTriangleInverts) {
  for (uint32_t i = 0; i < 256; ++i) {
    const Point2 u = MultiJitteredSample(i, 256, 11);
    const auto [b0, b1] = SampleUniformTriangle(u);
    EXPECT_GE(b0, 0);
    EXPECT_GE(b1, 0);
    EXPECT_LE(b0 + b1, 1 + 1e-12);
    const Point2 back = InvertUniformTriangleSample(b0, b1);
    EXPECT_NEAR(back.x, u.x, 1e-12);
    EXPECT_NEAR(back.y, u.y, 1e-12);
  }
}

TEST(Sampling, MultiJitteredIsStratifiedInEachDimension) {
  for (uint32_t n : {16u, 64u, 100u}) {
    std::set<int> xs, ys;
    for (uint32_t i = 0; i < n; ++i) {
      const Point2 p = MultiJitteredSample(i, n, 1234);
      ASSERT_GE(p.x, 0);
      ASSERT_LT(p.x, 1);
      xs.insert(static_cast<int>(p.x * n));
      ys.insert(static_cast<int>(p.y * n));
    }
    EXPECT_EQ(xs.size(), n);  // one sample per 1/n column
    EXPECT_EQ(ys.size(), n);
  }
}

// The set-at-once form is the sample-at-a-time one, bit for bit, at every kind of size:
// one sample, powers of two, squares and neither.
TEST(Sampling, MultiJitteredSamplesAreTheSingleSamples) {
  for (uint32_t n : {1u, 2u, 3u, 4u, 5u, 9u, 12u, 16u, 64u, 100u, 257u}) {
    for (uint32_t p : {0u, 1u, 7u, 0x9e3779b9u, 0xffffffffu}) {
      std::vector<Point2> all(n);
      MultiJitteredSamples(p, all);
      for (uint32_t i = 0; i < n; ++i) {
        const Point2 one = MultiJitteredSample(i, n, p);
        ASSERT_EQ(all[i].x, one.x) << n << " " << p << " " << i;
        ASSERT_EQ(all[i].y, one.y) << n << " " << p << " " << i;
      }
    }
  }
}

// Several sets at once, within the inline buffer and beyond it: set k is pattern k's points.
TEST(Sampling, MultiJitteredSetsAreEachPatternsSamples) {
  for (uint32_t n : {1u, 4u, 16u, 21u, 40u}) {
    const std::array<uint32_t, 3> patterns = {3u, 0x9e3779b9u, 11u};
    const MultiJitteredSets<3> sets(patterns, n);
    for (size_t k = 0; k < patterns.size(); ++k) {
      ASSERT_EQ(sets[k].size(), n);
      for (uint32_t i = 0; i < n; ++i) {
        const Point2 one = MultiJitteredSample(i, n, patterns[k]);
        ASSERT_EQ(sets[k][i].x, one.x) << n << " " << k << " " << i;
        ASSERT_EQ(sets[k][i].y, one.y) << n << " " << k << " " << i;
      }
    }
  }
}

TEST(Sampling, PatternSeedsDependOnSeedAndIndex) {
  EXPECT_NE(PatternSeed(1, 2), PatternSeed(1, 3));
  EXPECT_NE(PatternSeed(1, 2), PatternSeed(2, 2));
  EXPECT_EQ(PatternSeed(5, 9, 1), PatternSeed(5, 9, 1));
}

}  // namespace
}  // namespace radflux
