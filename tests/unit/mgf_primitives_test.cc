// MGF primitives: tessellated areas against closed forms within the stated error (pi/n)^2,
// exactly against the inscribed polygons where that is simple, and orientation through the
// signed volume (divergence theorem) of the closed ones.
#include "solver/scene/mgf_primitives.h"

#include <cmath>
#include <numbers>

#include "gtest/gtest.h"
#include "solver/scene/scene.h"

namespace radflux {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<Vec3> Polygon(const MgfMesh& mesh, const std::vector<uint32_t>& face) {
  std::vector<Vec3> p;
  for (uint32_t v : face) p.push_back(mesh.points[v]);
  return p;
}

double Area(const MgfMesh& mesh) {
  double area = 0;
  for (const auto& face : mesh.faces) area += Length(PolygonNewellNormal(Polygon(mesh, face))) / 2;
  return area;
}

// Signed volume enclosed (positive when the faces face outward).
double Volume(const MgfMesh& mesh) {
  double volume = 0;
  for (const auto& face : mesh.faces) {
    const std::vector<Vec3> p = Polygon(mesh, face);
    for (size_t i = 1; i + 1 < p.size(); ++i) volume += Dot(p[0], Cross(p[i], p[i + 1])) / 6;
  }
  return volume;
}

double Bound(int n) { return (kPi / n) * (kPi / n); }

TEST(MgfPrimitives, CylinderAreaIsTheInscribedPrismSide) {
  for (int n : {3, 16, 64}) {
    absl::StatusOr<MgfMesh> m = TessellateCone({1, 2, 3}, 0.5, {1, 2, 5}, 0.5, n);
    ASSERT_TRUE(m.ok()) << m.status();
    EXPECT_EQ(m->faces.size(), static_cast<size_t>(n));
    const double exact = 2 * kPi * 0.5 * 2;
    EXPECT_NEAR(Area(*m), n * 2 * 0.5 * std::sin(kPi / n) * 2, 1e-12);
    EXPECT_LT(Area(*m), exact);
    EXPECT_GT(Area(*m), exact * (1 - Bound(n)));
  }
}

TEST(MgfPrimitives, CylinderFacesPointAwayFromTheAxisAndInwardForNegativeRadius) {
  for (double r : {0.5, -0.5}) {
    absl::StatusOr<MgfMesh> m = TessellateCone({0, 0, 0}, r, {0, 0, 1}, r, 16);
    ASSERT_TRUE(m.ok());
    for (const auto& face : m->faces) {
      const std::vector<Vec3> p = Polygon(*m, face);
      Vec3 c;
      for (const Vec3& q : p) c += q / static_cast<double>(p.size());
      const Vec3 radial(c.x, c.y, 0);
      EXPECT_GT(Dot(PolygonNewellNormal(p), radial) * r, 0);
    }
  }
}

TEST(MgfPrimitives, ConeFrustumArea) {
  const double r1 = 1.0, r2 = 0.25, h = 3.0;
  for (int n : {8, 32, 128}) {
    absl::StatusOr<MgfMesh> m = TessellateCone({0, 0, 0}, r1, {0, 0, h}, r2, n);
    ASSERT_TRUE(m.ok());
    const double s = std::sin(kPi / n), c = std::cos(kPi / n);
    // n isosceles trapezoids with parallel sides 2 r s and height sqrt(h^2 + (dr c)^2).
    EXPECT_NEAR(Area(*m), n * (r1 + r2) * s * std::hypot(h, (r1 - r2) * c), 1e-12);
    const double exact = kPi * (r1 + r2) * std::hypot(h, r1 - r2);
    EXPECT_LE(Area(*m), exact);
    EXPECT_GT(Area(*m), exact * (1 - Bound(n)));
  }
  absl::StatusOr<MgfMesh> tip = TessellateCone({0, 0, 0}, 0, {0, 0, 1}, 1, 12);
  ASSERT_TRUE(tip.ok());
  for (const auto& face : tip->faces) EXPECT_EQ(face.size(), 3u);
}

TEST(MgfPrimitives, RingArea) {
  for (int n : {6, 16, 100}) {
    absl::StatusOr<MgfMesh> m = TessellateRing({0, 0, 1}, {0, 0, 2}, 0.5, 2.0, n);
    ASSERT_TRUE(m.ok());
    const double exact = kPi * (4.0 - 0.25);
    EXPECT_NEAR(Area(*m), exact * std::sin(2 * kPi / n) / (2 * kPi / n), 1e-12);
    EXPECT_GT(Area(*m), exact * (1 - Bound(n)));
    for (const auto& face : m->faces) EXPECT_GT(PolygonNewellNormal(Polygon(*m, face)).z, 0);
  }
  absl::StatusOr<MgfMesh> disk = TessellateRing({0, 0, 0}, {0, -1, 0}, 0, 1, 16);
  ASSERT_TRUE(disk.ok());
  EXPECT_EQ(disk->faces.size(), 16u);
  for (const auto& face : disk->faces) EXPECT_LT(PolygonNewellNormal(Polygon(*disk, face)).y, 0);
}

TEST(MgfPrimitives, SphereAreaAndVolumeOutward) {
  const double r = 1.5;
  for (int n : {4, 16, 64, 256}) {
    absl::StatusOr<MgfMesh> m = TessellateSphere({1, -1, 2}, r, n);
    ASSERT_TRUE(m.ok());
    const double area = 4 * kPi * r * r;
    EXPECT_LT(Area(*m), area);
    EXPECT_GT(Area(*m), area * (1 - Bound(n))) << n;
    const double volume = Volume(*m);
    EXPECT_GT(volume, 0);
    EXPECT_LT(volume, 4 * kPi * r * r * r / 3);
  }
  absl::StatusOr<MgfMesh> inward = TessellateSphere({0, 0, 0}, -1, 16);
  ASSERT_TRUE(inward.ok());
  EXPECT_LT(Volume(*inward), 0);
}

TEST(MgfPrimitives, TorusAreaAndVolumeOutward) {
  // r_in 1.1, r_out 1.4: major radius 1.25, tube radius 0.15 (corridor.mgf's ring).
  const double big = 1.25, small = 0.15;
  for (int n : {8, 16, 64}) {
    absl::StatusOr<MgfMesh> m = TessellateTorus({0, 0, 0}, {1, 0, 0}, 1.1, 1.4, n);
    ASSERT_TRUE(m.ok());
    EXPECT_EQ(m->faces.size(), static_cast<size_t>(n * n));
    const double area = 4 * kPi * kPi * big * small;
    EXPECT_LT(Area(*m), area);
    EXPECT_GT(Area(*m), area * (1 - Bound(n))) << n;
    EXPECT_GT(Volume(*m), 2 * kPi * kPi * big * small * small * (1 - 2 * Bound(n)));
  }
  absl::StatusOr<MgfMesh> inward = TessellateTorus({0, 0, 0}, {0, 0, 1}, -1.1, -1.4, 16);
  ASSERT_TRUE(inward.ok());
  EXPECT_LT(Volume(*inward), 0);
}

TEST(MgfPrimitives, PrismIsAClosedSolidFacingOut) {
  // An L-shaped (non-convex) base of area 3 in the z = 0 plane, counter-clockwise about +z.
  const std::vector<Vec3> base = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  absl::StatusOr<MgfMesh> m = ExtrudePrism(base, 0.5);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->faces.size(), base.size() + 2);
  EXPECT_NEAR(Volume(*m), 3 * 0.5, 1e-12);
  EXPECT_NEAR(Area(*m), 2 * 3 + 8 * 0.5, 1e-12);  // two caps + perimeter 8 x length
  for (size_t i = 0; i < base.size(); ++i) EXPECT_NEAR(m->points[base.size() + i].z, -0.5, 1e-15);
}

TEST(MgfPrimitives, BadArgumentsAreErrors) {
  EXPECT_FALSE(TessellateSphere({0, 0, 0}, 0, 16).ok());
  EXPECT_FALSE(TessellateSphere({0, 0, 0}, 1, 2).ok());
  EXPECT_FALSE(TessellateCone({0, 0, 0}, 1, {0, 0, 0}, 1, 16).ok());
  EXPECT_FALSE(TessellateCone({0, 0, 0}, 1, {0, 0, 1}, -1, 16).ok());
  EXPECT_FALSE(TessellateCone({0, 0, 0}, 0, {0, 0, 1}, 0, 16).ok());
  EXPECT_FALSE(TessellateRing({0, 0, 0}, {0, 0, 0}, 0, 1, 16).ok());
  EXPECT_FALSE(TessellateRing({0, 0, 0}, {0, 0, 1}, 1, 1, 16).ok());
  EXPECT_FALSE(TessellateTorus({0, 0, 0}, {0, 0, 1}, 1.4, 1.1, 16).ok());
  EXPECT_FALSE(ExtrudePrism({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, 1).ok());
  EXPECT_FALSE(ExtrudePrism({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 0).ok());
}

TEST(MgfPrimitives, HoleIsBridgedIntoOneContourOfTheRightArea) {
  const std::vector<Vec3> outer = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  // Wound like the outer contour on purpose: it must be reversed.
  const std::vector<Vec3> hole = {{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
  absl::StatusOr<std::vector<uint32_t>> order = BridgeHoles(outer, {hole});
  ASSERT_TRUE(order.ok()) << order.status();
  EXPECT_EQ(order->size(), 4u + 4u + 2u);  // both bridge ends visited twice
  std::vector<Vec3> all = outer;
  all.insert(all.end(), hole.begin(), hole.end());
  std::vector<Vec3> contour;
  for (uint32_t k : *order) contour.push_back(all[k]);
  EXPECT_NEAR(PolygonNewellNormal(contour).z / 2, 16 - 1, 1e-12);
  EXPECT_FALSE(BridgeHoles({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {hole}).ok());
}

}  // namespace
}  // namespace radflux
