#include <gtest/gtest.h>

#include <cmath>

#include "solver/output/camera.h"
#include "solver/output/tone_map.h"

namespace radflux {
namespace {

TEST(OutputToneMap, ScaleStopsClampAndSrgb) {
  ToneMapOptions tone;
  tone.scale = 0.5;
  tone.exposure_stops = 2;  // x4: total x2
  EXPECT_DOUBLE_EQ(ToneMapLinear(0.25, tone), 0.5);
  EXPECT_DOUBLE_EQ(ToneMapLinear(3, tone), 1);
  EXPECT_DOUBLE_EQ(ToneMapLinear(-1, tone), 0);
  EXPECT_DOUBLE_EQ(ToneMapLinear(std::nan(""), tone), 0);
  EXPECT_NEAR(SrgbEncode(0.5), 0.735356983, 1e-9);
  EXPECT_DOUBLE_EQ(SrgbEncode(0.001), 0.01292);
  EXPECT_EQ(ToneMapByte(0.25, tone), 188);
  tone.srgb = false;
  EXPECT_EQ(ToneMapByte(0.25, tone), 128);
  EXPECT_DOUBLE_EQ(AutoExposureScale({{0, 0, 0}, {1, 2, 0}, {4, 0, 0}, {0, 0, 8}}, 0.5), 0.25);
  EXPECT_DOUBLE_EQ(AutoExposureScale({{0, 0, 0}}), 1);
}

TEST(OutputCamera, CornellCameraLooksDownZWithPositiveXOnTheLeft) {
  const Camera camera = CornellCamera(100, 100);
  ASSERT_TRUE(ValidateCamera(camera).ok());
  const PinholeProjection projection(camera);
  const Ray centre = projection.RayThrough(50, 50);
  EXPECT_EQ(centre.origin, Vec3(278, 273, -800));
  EXPECT_NEAR(centre.direction.z, 1, 1e-12);
  const Ray left = projection.RayThrough(0, 50);
  EXPECT_GT(left.direction.x, 0);  // +x (the red wall) on the left
  const Ray top = projection.RayThrough(50, 0);
  EXPECT_GT(top.direction.y, 0);  // row 0 is the top
  // The top edge is half the field of view above the axis.
  EXPECT_NEAR(std::atan2(top.direction.y, top.direction.z) * 360 / M_PI, 39.3077, 1e-9);
  EXPECT_NEAR(Length(left.direction), 1, 1e-12);
}

TEST(OutputCamera, DegenerateCamerasAreRejected) {
  Camera camera = CornellCamera(10, 10);
  camera.look_at = camera.position;
  EXPECT_FALSE(ValidateCamera(camera).ok());
  camera = CornellCamera(10, 10);
  camera.vertical_fov_degrees = 180;
  EXPECT_FALSE(ValidateCamera(camera).ok());
  camera = CornellCamera(10, -1);
  EXPECT_FALSE(ValidateCamera(camera).ok());
}

}  // namespace
}  // namespace radflux
