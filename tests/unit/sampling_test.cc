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

// The largest gap between neighbours of `v` on the circle [0, 1).
double LargestCircularGap(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  double gap = 1 - v.back() + v.front();
  for (size_t i = 1; i < v.size(); ++i) gap = std::max(gap, v[i] - v[i - 1]);
  return gap;
}

// A shifted shared set keeps each set stratified (one point per 1/n of each axis, up to the
// shift: no circular gap reaches 2/n) and, over patterns, covers the square uniformly (each
// of 4 x 4 cells gets 1/16 of the points within 4 standard deviations); the same pattern
// gives the same points.
TEST(Sampling, ShiftedMultiJitteredSamplesAreStratifiedAndUniformOverPatterns) {
  for (uint32_t n : {1u, 4u, 16u, 64u, 256u, 400u}) {  // 400: beyond the shared sizes
    std::array<double, 16> cells{};
    const uint32_t patterns = 4096;
    for (uint32_t p = 0; p < patterns; ++p) {
      std::vector<Point2> set(n), again(n);
      ShiftedMultiJitteredSamples(p, 1, set);
      ShiftedMultiJitteredSamples(p, 1, again);
      std::vector<double> xs, ys;
      for (uint32_t i = 0; i < n; ++i) {
        ASSERT_EQ(set[i].x, again[i].x);
        ASSERT_TRUE(set[i].x >= 0 && set[i].x < 1 && set[i].y >= 0 && set[i].y < 1);
        xs.push_back(set[i].x), ys.push_back(set[i].y);
        cells[static_cast<size_t>(4 * set[i].y) * 4 + static_cast<size_t>(4 * set[i].x)] += 1;
      }
      if (n > 1) {
        ASSERT_LT(LargestCircularGap(xs), 2.0 / n) << n << " " << p;
        ASSERT_LT(LargestCircularGap(ys), 2.0 / n) << n << " " << p;
      }
    }
    // A cell's count: at most binomial spread over patterns (less, as sets are stratified).
    const double total = static_cast<double>(patterns) * n, expected = total / 16;
    const double sd = std::sqrt(total * (1.0 / 16) * (15.0 / 16));
    for (double c : cells) EXPECT_NEAR(c, expected, 4 * sd) << n;
  }
  // Two streams of one size are two sets, not one set moved alike: their differences vary.
  std::vector<Point2> a(16), b(16);
  ShiftedMultiJitteredSamples(7, 1, a);
  ShiftedMultiJitteredSamples(7, 2, b);
  std::set<double> dx;
  for (size_t i = 0; i < a.size(); ++i)
    dx.insert(std::round(1e9 * std::fmod(b[i].x - a[i].x + 1, 1)));
  EXPECT_GT(dx.size(), 2u);
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

TEST(Sampling, BilinearInvertsAndItsPdfIsItsDensity) {
  for (const std::array<double, 4>& w :
       {std::array<double, 4>{1, 1, 1, 1}, {0.01, 1, 0.5, 2}, {3, 0.2, 0.01, 0.7}}) {
    // Round trip, and the pdf against a histogram of 65,536 stratified samples on 4 x 4 cells
    // (each cell's expected share is the bilinear pdf's integral over it, by a midpoint rule
    // on 16 x 16 points; a cell's count is within a few of it, far below the 2% tolerance).
    std::array<double, 16> count{};
    const uint32_t n = 65536;
    for (uint32_t i = 0; i < n; ++i) {
      const Point2 u = MultiJitteredSample(i, n, 29);
      const Point2 p = SampleBilinear(u, w);
      ASSERT_GE(p.x, 0);
      ASSERT_LT(p.x, 1);
      ASSERT_GE(p.y, 0);
      ASSERT_LT(p.y, 1);
      if (i % 64 == 0) {
        const Point2 back = InvertBilinearSample(p, w);
        EXPECT_NEAR(back.x, u.x, 1e-9);
        EXPECT_NEAR(back.y, u.y, 1e-9);
      }
      count[static_cast<size_t>(4 * std::floor(4 * p.y) + std::floor(4 * p.x))] += 1.0 / n;
    }
    for (int cy = 0; cy < 4; ++cy) {
      for (int cx = 0; cx < 4; ++cx) {
        double share = 0;
        for (int a = 0; a < 16; ++a) {
          for (int b = 0; b < 16; ++b) {
            share += BilinearPdf({(cx + (a + 0.5) / 16) / 4, (cy + (b + 0.5) / 16) / 4}, w) /
                     (16.0 * 16 * 16);
          }
        }
        EXPECT_NEAR(count[4 * cy + cx], share, 0.02 * share) << cx << "," << cy;
      }
    }
  }
  EXPECT_NEAR(LinearPdf(0.25, 1, 3), 2 * 1.5 / 4, 1e-15);
  EXPECT_NEAR(InvertLinearSample(SampleLinear(0.3, 0.2, 5), 0.2, 5), 0.3, 1e-12);
}

}  // namespace
}  // namespace radflux
