// The ray casters' hit normals and streams: Embree and the brute-force caster agree on the
// front side of what they hit (the row builders' back-face test uses it), and a stream
// (intersection or occlusion) returns what single rays return.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/raytrace/brute_force_ray_caster.h"
#include "test_scenes.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

using testing::RowFixture;

// Rays from points in and around the Cornell box in all directions: most hit the front of
// a patch, some its back (from outside the box or inside a block), some escape.
std::vector<Ray> CornellRays(int count) {
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const uint32_t n = static_cast<uint32_t>(count);
    const Point2 u = MultiJitteredSample(i, n, 7), w = MultiJitteredSample(i, n, 9);
    rays.push_back({{278 + 400 * (u.x - .5), 273 + 400 * (u.y - .5), 150 + 200 * u.x * u.y},
                    {std::cos(6.283 * w.x), w.y - .5, std::sin(6.283 * w.x)}});
  }
  return rays;
}

TEST(RayCaster, HitNormalsPointToThePatchFrontInBothCasters) {
  RowFixture fixture(*LoadObjFile(testing::SourcePath("scenes/cornell_box.obj")),
                     MeshOptions{300, 0});
  const BruteForceRayCaster brute(fixture.mesh);
  int hits = 0;
  for (const Ray& ray : CornellRays(400)) {
    for (const Hit& hit : {fixture.caster->Intersect(ray), brute.Intersect(ray)}) {
      if (hit.patch == kNoPatch) continue;
      ++hits;
      const Vec3& front = fixture.mesh.patches[hit.patch].normal;
      EXPECT_NEAR(Dot(Normalize(hit.normal), front), 1, 1e-5) << "patch " << hit.patch;
    }
  }
  EXPECT_GE(hits, 500);
}

TEST(RayCaster, StreamsReturnWhatSingleRaysReturn) {
  RowFixture fixture(*LoadObjFile(testing::SourcePath("scenes/cornell_box.obj")),
                     MeshOptions{300, 0});
  const BruteForceRayCaster brute(fixture.mesh);
  const std::vector<Ray> rays = CornellRays(400);
  int front = 0, back = 0;
  for (const RayCaster* caster : {static_cast<const RayCaster*>(fixture.caster.get()),
                                  static_cast<const RayCaster*>(&brute)}) {
    std::vector<StreamRay> stream(rays.size());
    for (size_t k = 0; k < rays.size(); ++k) {
      stream[k].SetOrigin(rays[k].origin);
      stream[k].SetDirection(rays[k].direction);
    }
    caster->IntersectStream(stream);
    for (size_t k = 0; k < rays.size(); ++k) {
      const Hit single = caster->Intersect(rays[k]);
      const StreamRay& s = stream[k];
      ASSERT_EQ(s.geom == kNoPatch, single.patch == kNoPatch) << "ray " << k;
      if (single.patch == kNoPatch) continue;
      EXPECT_EQ(s.prim, single.patch);
      EXPECT_NEAR(s.t_far, single.t, 1e-4 * single.t);
      const bool faces = Dot(rays[k].direction, fixture.mesh.patches[single.patch].normal) < 0;
      EXPECT_EQ(s.FrontPatch(), faces ? single.patch : kNoPatch);
      ++(faces ? front : back);
    }
  }
  EXPECT_GT(front, 500);
  EXPECT_GT(back, 0);  // both outcomes of the back-face test are exercised
}

// OccludedStream on segments of the same rays, cut at 0.5x and 2x the distance to their
// first hit (free, blocked), answers as Occluded does for each, in both casters.
TEST(RayCaster, OccludedStreamsReturnWhatSingleRaysReturn) {
  RowFixture fixture(*LoadObjFile(testing::SourcePath("scenes/cornell_box.obj")),
                     MeshOptions{300, 0});
  const BruteForceRayCaster brute(fixture.mesh);
  std::vector<Ray> segments;
  for (const Ray& ray : CornellRays(200)) {
    const Hit hit = fixture.caster->Intersect(ray);
    if (hit.patch == kNoPatch) continue;
    for (double f : {0.5, 2.0}) segments.push_back({ray.origin, ray.direction, 0, f * hit.t});
  }
  for (const RayCaster* caster : {static_cast<const RayCaster*>(fixture.caster.get()),
                                  static_cast<const RayCaster*>(&brute)}) {
    std::vector<StreamRay> stream(segments.size());
    for (size_t k = 0; k < segments.size(); ++k) {
      stream[k].SetOrigin(segments[k].origin);
      stream[k].SetDirection(segments[k].direction);
      stream[k].t_far = static_cast<float>(segments[k].t_far);
    }
    caster->OccludedStream(stream);
    int blocked = 0;
    for (size_t k = 0; k < segments.size(); ++k) {
      EXPECT_EQ(stream[k].Occluded(), k % 2 == 1) << "segment " << k;
      EXPECT_EQ(caster->Occluded(segments[k]), k % 2 == 1) << "segment " << k;
      blocked += stream[k].Occluded();
    }
    EXPECT_GT(blocked, 100);
  }
}

}  // namespace
}  // namespace radflux
