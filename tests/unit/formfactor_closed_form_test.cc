// Row builders against Howell's closed forms: each method within a stated tolerance,
// and the error shrinking as its knob (k, r, s) grows.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "howell_closed_forms.h"
#include "solver/formfactor/polygon_form_factor.h"
#include "test_scenes.h"

namespace radflux {
namespace {

using testing::ObjQuad;
using testing::RowFixture;
using testing::SceneFromObj;

// Plate "a" at z=0 facing +z and plate "b" at z=d facing -z, both 1 x 1 centred on the axis.
Scene ParallelSquares(double d) {
  int next = 1;
  std::string obj =
      ObjQuad("a", "white", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  obj += ObjQuad("b", "white", {{-.5, -.5, d}, {-.5, .5, d}, {.5, .5, d}, {.5, -.5, d}}, next);
  return SceneFromObj(obj);
}

// Floor "a" (w along x, l along y) and wall "b" (h along z) sharing the edge x=0.
Scene PerpendicularPlates(double w, double h, double l) {
  int next = 1;
  std::string obj = ObjQuad("a", "white", {{0, 0, 0}, {w, 0, 0}, {w, l, 0}, {0, l, 0}}, next);
  obj += ObjQuad("b", "white", {{0, 0, 0}, {0, l, 0}, {0, l, h}, {0, 0, h}}, next);
  return SceneFromObj(obj);
}

FormFactorOptions Method(FormFactorMethod m, int knob) {
  FormFactorOptions o;
  o.method = m;
  o.cutoff = 0;
  o.rays = knob;
  o.hemicube_res = knob;
  o.samples = knob;
  return o;
}

double ErrorFor(RowFixture& fixture, FormFactorMethod m, int knob, double exact) {
  const CsrMatrix f = fixture.Rows(Method(m, knob));
  return std::abs(fixture.SurfaceFormFactor(f, "a", "b") - exact);
}

struct Sweep {
  FormFactorMethod method;
  std::vector<int> knobs;  // increasing cost
  double tolerance;        // error bound at the largest knob
};

// Each method: the error at the largest knob is within tolerance, and it is smaller
// than at the smallest knob (the trend, not one point).
void CheckSweep(RowFixture& fixture, double exact, const Sweep& sweep) {
  std::vector<double> errors;
  for (int knob : sweep.knobs) errors.push_back(ErrorFor(fixture, sweep.method, knob, exact));
  for (size_t k = 0; k < errors.size(); ++k) {
    std::printf("  %-12s knob %5d  error %.2e\n", std::string(MethodName(sweep.method)).c_str(),
                sweep.knobs[k], errors[k]);
  }
  EXPECT_LT(errors.back(), sweep.tolerance) << MethodName(sweep.method);
  EXPECT_LT(errors.back(), errors.front()) << MethodName(sweep.method) << " does not converge";
}

TEST(FormFactorClosedForm, ParallelSquaresAtSeveralDistances) {
  for (double d : {0.5, 1.0, 2.0}) {
    const double exact = testing::ParallelRectangles(1, 1, d);
    RowFixture fixture(ParallelSquares(d), MeshOptions{16 * 2, 0});
    std::printf("parallel squares d=%g exact %.6f\n", d, exact);
    CheckSweep(fixture, exact, {FormFactorMethod::kMonteCarlo, {16, 256, 4096}, 0.004});
    CheckSweep(fixture, exact, {FormFactorMethod::kHemicube, {4, 16, 64}, 0.01});
    CheckSweep(fixture, exact, {FormFactorMethod::kAnalytic, {1, 16, 64}, 0.002});
  }
}

TEST(FormFactorClosedForm, PerpendicularRectanglesSharingAnEdge) {
  const double exact = testing::PerpendicularRectangles(1, 0.7, 1.3);
  RowFixture fixture(PerpendicularPlates(1, 0.7, 1.3), MeshOptions{64, 0});
  std::printf("perpendicular rectangles exact %.6f\n", exact);
  CheckSweep(fixture, exact, {FormFactorMethod::kMonteCarlo, {16, 256, 4096}, 0.004});
  CheckSweep(fixture, exact, {FormFactorMethod::kHemicube, {4, 16, 64}, 0.01});
  CheckSweep(fixture, exact, {FormFactorMethod::kAnalytic, {1, 16, 64}, 0.004});
}

// Coaxial discs as 48-gons (the polygon loses a relative 1 - sin(2pi/48)*48/(2pi) of area).
TEST(FormFactorClosedForm, CoaxialParallelDiscs) {
  const double r1 = 0.5, r2 = 0.8, h = 1.0;
  const int sides = 48;
  std::string obj;
  int next = 1;
  auto disc = [&](const std::string& name, double r, double z, bool up) {
    std::vector<Vec3> v;
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * std::numbers::pi * (up ? k : sides - k) / sides;
      v.push_back({r * std::cos(a), r * std::sin(a), z});
    }
    obj += ObjQuad(name, "white", v, next);
  };
  disc("a", r1, 0, true);
  disc("b", r2, h, false);
  // The exact value for the inscribed polygons: discs of equal area are a close proxy.
  const double shrink =
      std::sqrt(sides * std::sin(2 * std::numbers::pi / sides) / (2 * std::numbers::pi));
  const double exact = testing::CoaxialDiscs(r1 * shrink, r2 * shrink, h);
  RowFixture fixture(SceneFromObj(obj), MeshOptions{0, 0.45});
  std::printf("coaxial discs exact %.6f\n", exact);
  CheckSweep(fixture, exact, {FormFactorMethod::kMonteCarlo, {16, 256, 4096}, 0.005});
  CheckSweep(fixture, exact, {FormFactorMethod::kHemicube, {4, 16, 64}, 0.01});
  CheckSweep(fixture, exact, {FormFactorMethod::kAnalytic, {1, 4, 16}, 0.005});
}

// gamma / |a x b| of ContourEdgeTerm, from the same double cross and dot products, in long
// double: isolates the angle factor (series or atan2) from the products' own rounding.
long double AngleOverCrossLength(const Vec3& a, const Vec3& b) {
  const Vec3 c = Cross(a, b);
  const long double cross_len = std::sqrt(static_cast<long double>(Dot(c, c)));
  return std::atan2(cross_len, static_cast<long double>(Dot(a, b))) / cross_len;
}

TEST(FormFactorClosedForm, ContourEdgeTermIsWithinUlpsOfItsAtan2Form) {
  // Edges from 1e-5 to 3 radians wide at distances 1e-3 to 1e3, in many directions: both
  // the small-angle series and the atan2 form, and the switch between them.
  const Vec3 n = Normalize(Vec3{0.3, -0.2, 0.9});
  int series = 0, atan2_form = 0;
  double worst = 0;
  for (int i = 0; i < 4000; ++i) {
    const double distance = std::pow(10.0, -3 + 6 * ((i * 37) % 101) / 100.0);
    const double gamma = std::pow(10.0, -5 + 5.48 * ((i * 53) % 97) / 96.0);
    const double phi = 0.7 * i, tilt = 0.31 * i;
    const Vec3 a = Vec3{std::cos(phi), std::sin(phi), 0.4 * std::sin(tilt)} * distance;
    const Vec3 axis = Normalize(Cross(a, Vec3{std::sin(tilt), 1, std::cos(phi)}));
    // b: a rotated by gamma about `axis` (Rodrigues; axis is perpendicular to a).
    const Vec3 b =
        (a * std::cos(gamma) + Cross(axis, a) * std::sin(gamma)) * (1 + 0.3 * std::sin(i));
    const Vec3 c = Cross(a, b);
    if (Dot(n, c) == 0) continue;
    const double d = Dot(a, b);
    (d > 0 && Dot(c, c) < kSmallAngleTan2 * d * d ? series : atan2_form)++;
    const long double exact = AngleOverCrossLength(a, b);
    const double factor = ContourEdgeTerm(a, b, n) / Dot(n, c);
    worst = std::max(worst, static_cast<double>(std::abs(factor - exact) / exact));
    // The reversed edge's term is the exact negation, on either path.
    EXPECT_EQ(ContourEdgeTerm(b, a, n), -ContourEdgeTerm(a, b, n)) << i;
  }
  EXPECT_GT(series, 1000);
  EXPECT_GT(atan2_form, 500);
  EXPECT_LT(worst, 8 * std::numeric_limits<double>::epsilon())
      << series << " series, " << atan2_form << " atan2";
  EXPECT_EQ(ContourEdgeTerm({1, 0, 0}, {2, 0, 0}, n), 0.0);  // an edge pointing at x
  EXPECT_EQ(AtanOverTOfSquare(0), 1.0);
}

TEST(FormFactorClosedForm, PointFacingAPolygonIsExact) {
  // Differential area at the origin facing +z; a 0.8 x 1.5 rectangle at height 0.6 with
  // one corner on the normal.
  const std::vector<Vec3> rect{{0, 0, 0.6}, {0, 1.5, 0.6}, {0.8, 1.5, 0.6}, {0.8, 0, 0.6}};
  EXPECT_NEAR(PointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, rect),
              testing::PointToCornerRectangle(0.8, 1.5, 0.6), 1e-12);
  // The same rectangle seen from below its plane contributes nothing, tilted half-way it is
  // clipped.
  EXPECT_EQ(PointToPolygonFormFactor({0, 0, 1}, {0, 0, 1}, rect), 0.0);
  const std::vector<Vec3> straddling{{-1, -1, -1}, {1, -1, -1}, {1, 1, 1}, {-1, 1, 1}};
  const double half = PointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, straddling);
  EXPECT_GT(half, 0);
  EXPECT_LT(half, 0.5);
}

// A sliver lying along the clipping plane, its vertices rounded to alternate sides (a
// RenderPark office2 face overran the n + 1 vertices a convex clip gives): every edge crosses,
// so the clip keeps the 2 vertices in front and adds 4 crossings, within the 2n it promises.
TEST(FormFactorClosedForm, ClippingASliverAlongThePlaneStaysInItsRoom) {
  const std::vector<Vec3> sliver{{0, 0, 1e-17}, {1, 0, -1e-17}, {1, 1e-9, 1e-17}, {0, 1e-9, -1e-17}};
  const std::vector<Vec3> clipped = ClipPolygonToHalfSpace(sliver, {0, 0, 0}, {0, 0, 1});
  EXPECT_EQ(clipped.size(), 6u);
  for (const Vec3& p : clipped) EXPECT_GE(p.z, 0) << p.x << " " << p.y;
  std::array<Vec3, 8> out;
  const std::array<double, 4> distance{1e-17, -1e-17, 1e-17, -1e-17};
  EXPECT_EQ(ClipPolygonToHalfSpace(sliver, distance, out), 6u);
}

}  // namespace
}  // namespace radflux
