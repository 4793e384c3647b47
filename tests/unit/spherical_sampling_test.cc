// The spherical triangle (Arvo) and rectangle (Urena et al.) samplers: each against its
// inverse, against each other, against numeric integration of the solid angle, and their
// constant Jacobian (uniform in solid angle); and the mean of Omega cos / pi under them
// against Lambert's closed-form point-to-polygon form factor.
#include "solver/core/spherical_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "solver/formfactor/emitter_shape.h"
#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

// A rectangle tilted against the viewer, and viewpoints around it (in front, behind,
// grazing, close to a corner): the cases the row builder meets.
const SphericalRectangle kRect{{-0.3, 0.2, 1.0}, {1.2, 0.0, 0.3}, {0.0, 0.8, 0.0}};
const std::vector<Vec3> kViewpoints = {{0, 0, 0},          {0.4, 0.5, -2},  {2, -1, 3},
                                       {-0.29, 0.21, 0.9}, {0.3, 0.6, 1.3}, {5, 5, -5}};

std::array<Vec3, 4> Corners(const SphericalRectangle& r) {
  return {r.s, r.s + r.ex, r.s + r.ex + r.ey, r.s + r.ey};
}

// The solid angle of `rect` at p by a midpoint rule on an m x m grid of
// integral cos / r^2 dA.
double NumericSolidAngle(const SphericalRectangle& rect, const Vec3& p, int m) {
  const Vec3 n = Normalize(Cross(rect.ex, rect.ey));
  const double cell = Length(Cross(rect.ex, rect.ey)) / (m * m);
  double sum = 0;
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) {
      const Vec3 q = rect.s + rect.ex * ((a + 0.5) / m) + rect.ey * ((b + 0.5) / m);
      const Vec3 d = q - p;
      const double r2 = Dot(d, d);
      sum += std::abs(Dot(d, n)) / (r2 * std::sqrt(r2)) * cell;
    }
  }
  return sum;
}

TEST(SphericalSampling, SolidAnglesAgreeWithNumericIntegrationAndEachOther) {
  for (const Vec3& p : kViewpoints) {
    const auto c = Corners(kRect);
    const double rect = SphericalRectangleSolidAngle(kRect, p);
    const double triangles =
        SphericalTriangleArea(Normalize(c[0] - p), Normalize(c[1] - p), Normalize(c[2] - p)) +
        SphericalTriangleArea(Normalize(c[0] - p), Normalize(c[2] - p), Normalize(c[3] - p));
    EXPECT_NEAR(rect, triangles, 1e-12 * (1 + rect));
    // The midpoint rule on 800^2 cells: relative error well under 1e-4 except near a corner.
    EXPECT_NEAR(rect, NumericSolidAngle(kRect, p, 800), 2e-4 * rect) << p.x << "," << p.y;
    double pdf = 0;
    SampleSphericalRectangle(kRect, p, {0.3, 0.7}, &pdf);
    EXPECT_NEAR(pdf * rect, 1, 1e-9);
  }
  // An octant: the triangle of the three axes is an eighth of the sphere.
  EXPECT_NEAR(SphericalTriangleArea({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), std::numbers::pi / 2, 1e-14);
}

TEST(SphericalSampling, TriangleSampleInvertsAndStaysInside) {
  const auto c = Corners(kRect);
  const std::array<Vec3, 3> tri = {c[0], c[1], c[2]};
  for (const Vec3& p : kViewpoints) {
    const Vec3 n = Cross(tri[1] - tri[0], tri[2] - tri[0]);
    for (uint32_t i = 0; i < 256; ++i) {
      const Point2 u = MultiJitteredSample(i, 256, 11);
      double pdf = 0;
      const Vec3 w = SampleSphericalTriangle(tri, p, u, &pdf);
      EXPECT_NEAR(Length(w), 1, 1e-12);
      // The ray from p along w meets the triangle: barycentrics in [0, 1].
      const Vec3 q = p + w * (Dot(tri[0] - p, n) / Dot(w, n));
      const double n2 = Dot(n, n);
      const double b1 = Dot(Cross(q - tri[0], tri[2] - tri[0]), n) / n2;
      const double b2 = Dot(Cross(tri[1] - tri[0], q - tri[0]), n) / n2;
      EXPECT_GE(b1, -1e-9);
      EXPECT_GE(b2, -1e-9);
      EXPECT_LE(b1 + b2, 1 + 1e-9);
      const Point2 back = InvertSphericalTriangleSample(tri, p, w);
      EXPECT_NEAR(back.x, u.x, 1e-7) << p.x << " u " << u.x << "," << u.y;
      EXPECT_NEAR(back.y, u.y, 1e-7) << p.x << " u " << u.x << "," << u.y;
    }
  }
}

TEST(SphericalSampling, RectangleSampleInvertsAndStaysInside) {
  for (const Vec3& p : kViewpoints) {
    for (uint32_t i = 0; i < 256; ++i) {
      const Point2 u = MultiJitteredSample(i, 256, 13);
      const Vec3 q = SampleSphericalRectangle(kRect, p, u);
      const Vec3 local = q - kRect.s;
      const double a = Dot(local, kRect.ex) / Dot(kRect.ex, kRect.ex);
      const double b = Dot(local, kRect.ey) / Dot(kRect.ey, kRect.ey);
      EXPECT_NEAR(Dot(local, Cross(kRect.ex, kRect.ey)), 0, 1e-12);  // on the plane
      EXPECT_GE(a, -1e-12);
      EXPECT_LE(a, 1 + 1e-12);
      EXPECT_GE(b, -1e-12);
      EXPECT_LE(b, 1 + 1e-12);
      const Point2 back = InvertSphericalRectangleSample(kRect, p, q);
      EXPECT_NEAR(back.x, u.x, 1e-7) << p.x << " u " << u.x << "," << u.y;
      EXPECT_NEAR(back.y, u.y, 1e-7) << p.x << " u " << u.x << "," << u.y;
    }
  }
}

// Uniform in solid angle: a small square du x du of the unit square maps onto a patch of
// directions of solid angle Omega du^2 (the Jacobian is the constant Omega), by finite
// differences of the sampled directions.
template <class Direction>
void ExpectConstantJacobian(const Direction& direction, double solid_angle) {
  const double h = 1e-5;
  for (uint32_t i = 0; i < 64; ++i) {
    Point2 u = MultiJitteredSample(i, 64, 17);
    u = {0.02 + 0.96 * u.x, 0.02 + 0.96 * u.y};  // finite differences inside the square
    const Vec3 w = direction(u);
    const Vec3 du = (direction({u.x + h, u.y}) - direction({u.x - h, u.y})) / (2 * h);
    const Vec3 dv = (direction({u.x, u.y + h}) - direction({u.x, u.y - h})) / (2 * h);
    EXPECT_NEAR(std::abs(Dot(w, Cross(du, dv))), solid_angle, 1e-5 * solid_angle);
  }
}

TEST(SphericalSampling, BothMapsAreUniformInSolidAngle) {
  const auto c = Corners(kRect);
  const std::array<Vec3, 3> tri = {c[0], c[2], c[3]};
  for (const Vec3& p : kViewpoints) {
    ExpectConstantJacobian(
        [&](Point2 u) { return Normalize(SampleSphericalRectangle(kRect, p, u) - p); },
        SphericalRectangleSolidAngle(kRect, p));
    const double triangle =
        SphericalTriangleArea(Normalize(c[0] - p), Normalize(c[2] - p), Normalize(c[3] - p));
    ExpectConstantJacobian([&](Point2 u) { return SampleSphericalTriangle(tri, p, u); }, triangle);
  }
}

// E[Omega max(0, cos theta) / pi] over directions uniform in the polygon's solid angle is
// the point-to-polygon form factor. The rectangle, and the same rectangle as two triangles
// (each chosen in proportion to its solid angle), against Lambert's closed form: 4,096
// stratified samples, whose error is far below the 1e-3 tolerance.
TEST(SphericalSampling, MeanOfCosineIsLambertsFormFactor) {
  const auto c = Corners(kRect);
  const std::vector<Vec3> polygon(c.begin(), c.end());
  const std::array<std::array<Vec3, 3>, 2> halves = {{{c[0], c[1], c[2]}, {c[0], c[2], c[3]}}};
  for (const Vec3& n : {Vec3{0, 0, 1}, Normalize(Vec3{1, 0.5, 1})}) {
    const Vec3 p{0.1, 0.3, -0.2};
    const double exact = PointToPolygonFormFactor(p, n, polygon);
    const double omega = SphericalRectangleSolidAngle(kRect, p);
    double omega_half[2];
    for (int t = 0; t < 2; ++t) {
      const auto& h = halves[t];
      omega_half[t] =
          SphericalTriangleArea(Normalize(h[0] - p), Normalize(h[1] - p), Normalize(h[2] - p));
    }
    const uint32_t count = 4096;
    double rect_mean = 0, tri_mean = 0;
    for (uint32_t i = 0; i < count; ++i) {
      const Point2 u = MultiJitteredSample(i, count, 19);
      const Vec3 w = Normalize(SampleSphericalRectangle(kRect, p, u) - p);
      rect_mean += omega * std::max(0.0, Dot(w, n)) / std::numbers::pi / count;
      // The triangles: u.x picks one by its share of the solid angle, then is rescaled.
      const double share = omega_half[0] / (omega_half[0] + omega_half[1]);
      const int t = u.x < share ? 0 : 1;
      const Point2 v{t == 0 ? u.x / share : (u.x - share) / (1 - share), u.y};
      const Vec3 wt = SampleSphericalTriangle(halves[t], p, v);
      tri_mean +=
          (omega_half[0] + omega_half[1]) * std::max(0.0, Dot(wt, n)) / std::numbers::pi / count;
    }
    EXPECT_GT(exact, 0.05);
    EXPECT_NEAR(rect_mean, exact, 1e-3 * exact);
    EXPECT_NEAR(tri_mean, exact, 1e-3 * exact);
  }
}

// Tiny solid angles (a far, small patch) switch to area sampling with the exact
// per-steradian pdf; the pair stays each other's inverse and the pdf stays ~1 / Omega.
TEST(SphericalSampling, TinySolidAnglesKeepThePairConsistent) {
  const SphericalRectangle tiny{{0, 0, 1e4}, {1e-2, 0, 0}, {0, 1e-2, 0}};
  const Vec3 p{0.3, -0.2, 0};
  const double omega = SphericalRectangleSolidAngle(tiny, p);
  ASSERT_LT(omega, 1e-9);
  const auto c = Corners(tiny);
  const std::array<Vec3, 3> tri = {c[0], c[1], c[2]};
  for (uint32_t i = 0; i < 16; ++i) {
    const Point2 u = MultiJitteredSample(i, 16, 23);
    double pdf = 0;
    const Vec3 q = SampleSphericalRectangle(tiny, p, u, &pdf);
    EXPECT_NEAR(pdf * omega, 1, 1e-5);
    const Point2 back = InvertSphericalRectangleSample(tiny, p, q);
    EXPECT_NEAR(back.x, u.x, 1e-9);
    EXPECT_NEAR(back.y, u.y, 1e-9);
    const Vec3 w = SampleSphericalTriangle(tri, p, u, &pdf);
    EXPECT_NEAR(pdf * omega / 2, 1, 1e-5);
    const Point2 tback = InvertSphericalTriangleSample(tri, p, w);
    EXPECT_NEAR(tback.x, u.x, 1e-6);
    EXPECT_NEAR(tback.y, u.y, 1e-6);
  }
}

// The emitter sampler (solid-angle map composed with the cosine warp), for a rectangle, a
// triangle and a general quad: E[cos / (pi pdf)] is the point-to-polygon form factor, and
// with the warp the estimate's spread is small (the warp follows the cosine), here for a
// receiver beside the emitter, where the cosine runs from about 0 to 1 across it. The
// samples come from one EmitterPointSampler set up once (as light sampling uses it), and
// each equals a fresh SampleEmitterSolidAngle's bit for bit: the set-up keeps no state.
TEST(SphericalSampling, EmitterSamplesGiveLambertsFormFactor) {
  const auto c = Corners(kRect);
  PatchMesh mesh;
  mesh.positions = {c[0], c[1], c[2], c[3], c[0] + Vec3{0, -0.2, 0}};
  Patch rect, tri, quad;
  rect.v = {0, 1, 2, 3};
  tri.v = {0, 1, 2, 2};
  quad.v = {4, 1, 2, 3};  // not a rectangle: one corner moved
  for (Patch* p : {&rect, &tri, &quad}) {
    FinishPatch(mesh.positions, -Normalize(Cross(kRect.ex, kRect.ey)), *p);
    mesh.patches.push_back(*p);
  }
  const Vec3 x{-0.35, 0.5, 0.4};  // in front of the emitting side, close to its edge
  const Vec3 n = Normalize(Vec3{1, 0, 0.5});
  for (uint32_t p = 0; p < 3; ++p) {
    const EmitterShape shape = MakeEmitterShape(mesh, p, 1);
    EXPECT_EQ(shape.rectangle, p == 0);
    std::vector<Vec3> polygon(shape.corner.begin(), shape.corner.begin() + shape.corners);
    const double exact = PointToPolygonFormFactor(x, n, polygon);
    const uint32_t count = 4096;
    double mean = 0, mean2 = 0;
    const EmitterPointSampler sampler(shape, x, n);
    for (uint32_t i = 0; i < count; ++i) {
      const Point2 u = MultiJitteredSample(i, count, 31);
      const EmitterSample e = sampler(u);
      const EmitterSample fresh = SampleEmitterSolidAngle(shape, x, n, u);
      ASSERT_EQ(e.pdf, fresh.pdf);
      ASSERT_EQ(e.point.x, fresh.point.x);
      ASSERT_EQ(e.point.y, fresh.point.y);
      ASSERT_EQ(e.point.z, fresh.point.z);
      ASSERT_GT(e.pdf, 0);
      const double v = std::max(0.0, Dot(n, Normalize(e.point - x))) / (std::numbers::pi * e.pdf);
      mean += v / count;
      mean2 += v * v / count;
    }
    EXPECT_GT(exact, 0.02);
    EXPECT_NEAR(mean, exact, 2e-3 * exact) << p;
    EXPECT_LT(std::sqrt(mean2 - mean * mean), 0.5 * exact) << p;  // spread per sample
  }
}

}  // namespace
}  // namespace radflux
