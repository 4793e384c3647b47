// The blocker hierarchy (blocker_bvh.h) finds exactly the blockers that the per-blocker shaft
// test (ShaftMayHold) keeps, for every pair of a cluttered scene of random quadrilaterals.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "solver/formfactor/blocker_bvh.h"
#include "solver/formfactor/shaft_cull.h"

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

TEST(BlockerBvh, FindsTheSameBlockersAsTestingEachOne) {
  const std::vector<SurfaceShape> shapes = RandomSquares(120, 7);
  std::vector<uint32_t> blockers = PotentialBlockers(shapes);
  ASSERT_GT(blockers.size(), 100u);  // random orientations: nearly every square can block
  const BlockerBvh bvh(shapes, blockers);
  EXPECT_EQ(bvh.size(), blockers.size());
  std::vector<const SurfaceShape*> found;
  size_t total = 0;
  for (uint32_t i = 0; i < shapes.size(); ++i) {
    for (uint32_t j = 0; j < shapes.size(); ++j) {
      if (i == j) continue;
      bvh.Query(i, j, found);
      std::vector<const SurfaceShape*> expected;
      for (uint32_t k : blockers) {
        if (ShaftMayHold(shapes[i], shapes[j], shapes[k])) expected.push_back(&shapes[k]);
      }
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, expected) << "pair " << i << " " << j;
      total += found.size();
    }
  }
  EXPECT_GT(total, 1000u);  // the scene is cluttered: the test compares real work
}

TEST(BlockerBvh, EmptyHierarchyFindsNothing) {
  const std::vector<SurfaceShape> shapes = RandomSquares(3, 1);
  const BlockerBvh bvh(shapes, {});
  std::vector<const SurfaceShape*> found{&shapes[0]};
  bvh.Query(0, 1, found);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace radflux
