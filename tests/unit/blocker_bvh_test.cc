// The blocker hierarchy (blocker_bvh.h) says a pair's shaft holds a blocker exactly when
// testing every blocker does (ShaftMayHold), and the candidates it lists lose nothing: the
// visible fraction over them equals the one over every blocker that may block the pair, for
// every pair of a cluttered scene of random quadrilaterals.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solver/formfactor/blocker_bvh.h"
#include "solver/formfactor/shaft_cull.h"
#include "solver/formfactor/shaft_visibility.h"

namespace radflux {
namespace {

std::vector<SurfaceShape> RandomSquares(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0, 10), size(0.2, 1.5), dir(-1, 1);
  std::vector<SurfaceShape> shapes;
  for (int k = 0; k < count; ++k) {
    const Vec3 o{pos(rng), pos(rng), pos(rng)};
    Vec3 n = Normalize(Vec3{dir(rng), dir(rng), dir(rng)});
    const Frame f = Frame::FromNormal(n);
    const double s = size(rng);
    shapes.push_back(MakeSurfaceShape({o, o + f.s * s, o + f.s * s + f.t * s, o + f.t * s}));
  }
  return shapes;
}

TEST(BlockerBvh, AnswersAsTestingEachBlocker) {
  const std::vector<SurfaceShape> shapes = RandomSquares(120, 7);
  std::vector<uint32_t> blockers = PotentialBlockers(shapes);
  ASSERT_GT(blockers.size(), 100u);  // random orientations: nearly every square can block
  const BlockerBvh bvh(shapes, blockers);
  EXPECT_EQ(bvh.size(), blockers.size());
  int in_shaft = 0, hidden = 0;
  std::vector<uint32_t> found;
  for (uint32_t i = 0; i < shapes.size(); ++i) {
    for (uint32_t j = 0; j < shapes.size(); ++j) {
      if (i == j) continue;
      bool any = false;
      std::vector<uint32_t> may_block;
      for (uint32_t k : blockers) {
        any = any || ShaftMayHold(shapes[i], shapes[j], shapes[k]);
        if (k != i && k != j && MayBlockPair(shapes[i], shapes[j], shapes[k])) may_block.push_back(k);
      }
      ASSERT_EQ(bvh.InShaft(i, j, found), any) << "pair " << i << " " << j;
      in_shaft += any;
      if (!any) continue;
      uint64_t segments = 0;
      const double all = VisibleFraction(shapes[i], shapes[j], shapes, may_block, segments);
      ASSERT_EQ(VisibleFraction(shapes[i], shapes[j], shapes, found, segments), all)
          << "pair " << i << " " << j;
      hidden += all < 1;
    }
  }
  // The scene is cluttered: both answers are often yes, and often no.
  EXPECT_GT(in_shaft, 2000);
  EXPECT_LT(in_shaft, 14000);
  EXPECT_GT(hidden, 1000);
}

TEST(BlockerBvh, EmptyHierarchyFindsNothing) {
  const std::vector<SurfaceShape> shapes = RandomSquares(3, 1);
  const BlockerBvh bvh(shapes, {});
  std::vector<uint32_t> found{7};
  EXPECT_FALSE(bvh.InShaft(0, 1, found));
  EXPECT_TRUE(found.empty());
}

TEST(BlockerBvh, APartlyTransparentBlockerLetsThroughItsTransparentFraction) {
  // 16 pairs of unit squares at z = 0 (facing up) and z = 2 (facing down), a wide plate at
  // z = 1 of opacity 0.3 between them: of their 16 x 256 segments 0.3 (kernel-weighted) are
  // blocked within 5 sigma, the same segments always alike, and all of them at opacity 1.
  constexpr int kPairs = 16;
  std::vector<SurfaceShape> shapes = {
      MakeSurfaceShape({{-5, -5, 1}, {3 * kPairs + 5, -5, 1}, {3 * kPairs + 5, 6, 1}, {-5, 6, 1}})};
  for (int p = 0; p < kPairs; ++p) {
    const double x = 3.0 * p;
    shapes.push_back(MakeSurfaceShape({{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}}));
    shapes.push_back(MakeSurfaceShape({{x, 0, 2}, {x, 1, 2}, {x + 1, 1, 2}, {x + 1, 0, 2}}));
  }
  shapes[0].opacity = 0.3f;
  const std::vector<uint32_t> plate{0};
  double visible = 0;
  uint64_t segments = 0;
  for (int p = 0; p < kPairs; ++p) {
    const SurfaceShape &a = shapes[1 + 2 * p], &b = shapes[2 + 2 * p];
    const double here = VisibleFraction(a, b, shapes, plate, segments);
    EXPECT_EQ(VisibleFraction(a, b, shapes, plate, segments), here);
    visible += here / kPairs;
  }
  const double n = static_cast<double>(segments) / 2;
  ASSERT_EQ(n, kPairs * 256);
  EXPECT_NEAR(1 - visible, 0.3, 5 * std::sqrt(0.3 * 0.7 / n));
  shapes[0].opacity = 1;
  EXPECT_EQ(VisibleFraction(shapes[1], shapes[2], shapes, plate, segments), 0.0) << "opaque: always";
}

}  // namespace
}  // namespace radflux
