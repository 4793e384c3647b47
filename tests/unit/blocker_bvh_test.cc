// The blocker hierarchy (blocker_bvh.h) answers as testing every blocker does (ShaftMayHold,
// SegmentHitsSurface with MayBlockPair), for every pair of a cluttered scene of random quadrilaterals.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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
  int in_shaft = 0, blocked = 0;
  for (uint32_t i = 0; i < shapes.size(); ++i) {
    for (uint32_t j = 0; j < shapes.size(); ++j) {
      if (i == j) continue;
      bool any = false;
      for (uint32_t k : blockers) any = any || ShaftMayHold(shapes[i], shapes[j], shapes[k]);
      ASSERT_EQ(bvh.AnyInShaft(i, j), any) << "pair " << i << " " << j;
      in_shaft += any;
      // A segment between points of i and j (at a third of the way to two vertices).
      const Vec3 a = shapes[i].centroid + (shapes[i].polygon[j % 4] - shapes[i].centroid) / 3;
      const Vec3 b = shapes[j].centroid + (shapes[j].polygon[i % 4] - shapes[j].centroid) / 3;
      bool hit = false;
      for (uint32_t k : blockers) {
        hit = hit || (k != i && k != j && SegmentHitsSurface(a, b, shapes[k]) &&
                      MayBlockPair(shapes[i], shapes[j], shapes[k]));
      }
      ASSERT_EQ(bvh.SegmentBlocked(a, b, i, j), hit) << "pair " << i << " " << j;
      blocked += hit;
    }
  }
  // The scene is cluttered: both answers are often yes, and often no.
  EXPECT_GT(in_shaft, 2000);
  EXPECT_LT(in_shaft, 14000);
  EXPECT_GT(blocked, 1000);
}

// Far from the origin single precision cannot place a segment within a blocker's size, and
// segments aimed at a blocker's vertices and edge midpoints graze its box: the padded
// single-precision node boxes still keep every blocker the exact test finds (and a segment
// with an end far outside the scene, tested against every blocker, answers alike).
TEST(BlockerBvh, AnswersAsTestingEachBlockerFarFromTheOrigin) {
  std::vector<SurfaceShape> shapes;
  for (SurfaceShape& s : RandomSquares(80, 13)) {
    std::vector<Vec3> moved = s.polygon;
    for (Vec3& p : moved) p = p + Vec3{3.7e5, -2.1e5, 1.3e4};
    shapes.push_back(MakeSurfaceShape(moved));
  }
  const std::vector<uint32_t> blockers = PotentialBlockers(shapes);
  const BlockerBvh bvh(shapes, blockers);
  int blocked = 0;
  for (uint32_t i = 0; i < shapes.size(); ++i) {
    for (uint32_t k = 0; k < shapes.size(); ++k) {
      if (k == i) continue;
      const Vec3 a = shapes[i].centroid;
      const std::vector<Vec3>& q = shapes[k].polygon;
      for (size_t v = 0; v < 2 * q.size(); ++v) {  // through k's vertices and edge midpoints
        const Vec3 aim = v % 2 == 0 ? q[v / 2] : (q[v / 2] + q[(v / 2 + 1) % q.size()]) * 0.5;
        const Vec3 b = a + (aim - a) * (v < 4 ? 2.0 : 1.5);
        const uint32_t j = (i + k + v) % shapes.size() == i ? k : (i + k + v) % shapes.size();
        bool hit = false;
        for (uint32_t c : blockers) {
          hit = hit || (c != i && c != j && SegmentHitsSurface(a, b, shapes[c]) &&
                        MayBlockPair(shapes[i], shapes[j], shapes[c]));
        }
        ASSERT_EQ(bvh.SegmentBlocked(a, b, i, j), hit) << i << " " << k << " " << v;
        blocked += hit;
      }
    }
  }
  EXPECT_GT(blocked, 1000);
  const Vec3 far = shapes[0].centroid * 3;  // beyond twice the scene's reach
  bool hit = false;
  for (uint32_t c : blockers) {
    hit = hit || (c != 0 && c != 1 && SegmentHitsSurface(far, shapes[1].centroid, shapes[c]) &&
                  MayBlockPair(shapes[0], shapes[1], shapes[c]));
  }
  EXPECT_EQ(bvh.SegmentBlocked(far, shapes[1].centroid, 0, 1), hit);
}

// SegmentBlocked with a remembered blocker (`last`, kept across a pair's segments) answers as
// without it; after a blocked segment it names a blocker that blocks that segment.
TEST(BlockerBvh, TheRememberedBlockerChangesNoAnswer) {
  const std::vector<SurfaceShape> shapes = RandomSquares(120, 11);
  const BlockerBvh bvh(shapes, PotentialBlockers(shapes));
  int reused = 0;
  for (uint32_t i = 0; i < shapes.size(); i += 3) {
    for (uint32_t j = 1; j < shapes.size(); j += 2) {
      if (i == j) continue;
      uint32_t last = BlockerBvh::kNoBlocker;
      for (int s = 0; s < 16; ++s) {  // 4 x 4 segments between points near each centroid
        const Vec3 a = shapes[i].centroid + (shapes[i].polygon[s % 4] - shapes[i].centroid) / 3;
        const Vec3 b = shapes[j].centroid + (shapes[j].polygon[s / 4] - shapes[j].centroid) / 4;
        const uint32_t before = last;
        const bool hit = bvh.SegmentBlocked(a, b, i, j, last);
        ASSERT_EQ(hit, bvh.SegmentBlocked(a, b, i, j)) << "pair " << i << " " << j;
        if (!hit) continue;
        ASSERT_NE(last, BlockerBvh::kNoBlocker);
        EXPECT_TRUE(SegmentHitsSurface(a, b, shapes[last]));
        reused += last == before;
      }
    }
  }
  EXPECT_GT(reused, 500) << "a pair's segments are often hidden by the same blocker";
}

// PotentialBlockers (with its quick rule: the scene's box in front of the plane) finds exactly
// the surfaces with some vertex behind them: random squares in a closed room, whose walls,
// 1e-7 off flat, block nothing, plus a square just inside the floor, whose plane has the
// floor within the coplanar band, and one 1e-3 above it, which has the floor behind.
TEST(BlockerBvh, PotentialBlockersAreTheSurfacesWithSomethingBehind) {
  std::vector<SurfaceShape> shapes = RandomSquares(60, 5);
  const double lo = -2, hi = 13, w = hi - lo;  // the squares reach -1.5 and 11.5
  const Vec3 x{w, 0, 0}, y{0, w, 0}, z{0, 0, w}, o{lo, lo, lo}, t = o + x + y + z;
  for (const auto& [origin, u, v] : {std::array{o, x, y}, std::array{o, z, x}, std::array{o, y, z},
                                     std::array{t, -y, -x}, std::array{t, -x, -z},
                                     std::array{t, -z, -y}}) {
    const Vec3 off = Normalize(Cross(u, v)) * 1e-7;  // one corner a little into the room
    shapes.push_back(MakeSurfaceShape({origin, origin + u, origin + u + v + off, origin + v}));
  }
  const size_t walls = shapes.size();
  shapes.push_back(MakeSurfaceShape({{0, 0, lo + 1e-9}, {1, 0, lo}, {1, 1, lo + 1e-9}, {0, 1, lo}}));
  shapes.push_back(MakeSurfaceShape({{0, 0, lo + 1e-3}, {1, 0, lo + 1e-3}, {1, 1, lo + 1e-3},
                                     {0, 1, lo + 1e-3}}));
  std::vector<uint32_t> brute;
  for (uint32_t k = 0; k < shapes.size(); ++k) {
    bool behind = false;
    for (const SurfaceShape& other : shapes) behind = behind || PartlyBehind(shapes[k], other);
    if (behind) brute.push_back(k);
  }
  EXPECT_EQ(PotentialBlockers(shapes), brute);
  for (size_t k = walls - 6; k < walls + 1; ++k) {
    EXPECT_FALSE(std::binary_search(brute.begin(), brute.end(), k)) << "wall or floor tile " << k;
  }
  EXPECT_TRUE(std::binary_search(brute.begin(), brute.end(), walls + 1));
  EXPECT_GT(brute.size(), 40u);
}

TEST(BlockerBvh, EmptyHierarchyFindsNothing) {
  const std::vector<SurfaceShape> shapes = RandomSquares(3, 1);
  const BlockerBvh bvh(shapes, {});
  EXPECT_FALSE(bvh.AnyInShaft(0, 1));
  EXPECT_FALSE(bvh.SegmentBlocked(shapes[0].centroid, shapes[1].centroid, 0, 1));
}

TEST(BlockerBvh, APartlyTransparentBlockerLetsThroughItsTransparentFraction) {
  // Unit squares at z = 0 (facing up) and z = 2 (facing down), a wide plate at z = 1 of
  // opacity 0.3 between them: of 4,096 segments between them 0.3 are blocked within 4
  // sigma, and the same segment always gets the same answer.
  std::vector<SurfaceShape> shapes = {
      MakeSurfaceShape({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}),
      MakeSurfaceShape({{0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}}),
      MakeSurfaceShape({{-5, -5, 1}, {6, -5, 1}, {6, 6, 1}, {-5, 6, 1}})};
  shapes[2].opacity = 0.3f;
  const BlockerBvh bvh(shapes, {2});
  constexpr int kSide = 64;
  int blocked = 0;
  for (int a = 0; a < kSide; ++a) {
    for (int b = 0; b < kSide; ++b) {
      const Vec3 x{(a + 0.5) / kSide, (b + 0.5) / kSide, 0};
      const Vec3 y{(b + 0.5) / kSide, (a + 0.5) / kSide, 2};
      const bool here = bvh.SegmentBlocked(x, y, 0, 1);
      EXPECT_EQ(bvh.SegmentBlocked(x, y, 0, 1), here);
      blocked += here;
    }
  }
  const double n = kSide * kSide;
  EXPECT_NEAR(blocked / n, 0.3, 4 * std::sqrt(0.3 * 0.7 / n));
  shapes[2].opacity = 1;
  EXPECT_TRUE(bvh.SegmentBlocked({0.5, 0.5, 0}, {0.5, 0.5, 2}, 0, 1)) << "opaque: always";
}

}  // namespace
}  // namespace radflux
