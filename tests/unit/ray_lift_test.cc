// How far a ray's origin is lifted off its surface (RayEpsilonFor): little enough that a face
// a hair's breadth away is still met, enough that a ray far from the origin never meets the
// face it starts on. Both read from Monte Carlo rows, where a lost ray shows as a missing 1/k.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "howell_closed_forms.h"
#include "solver/core/vec3.h"
#include "solver/formfactor/row_builder.h"
#include "test_scenes.h"

namespace radflux {
namespace {

using testing::ObjQuad;
using testing::RowFixture;
using testing::SceneFromObj;

// Plain ray counts: every entry is hits / k (no light sampling, no averaging by reciprocity,
// no exposure scaling), so a row's sum is the share of its rays that met a front side.
FormFactorOptions CountedRows() {
  FormFactorOptions o;
  o.method = FormFactorMethod::kMonteCarlo;
  o.rays = 1024;
  o.cutoff = 0;
  o.reciprocal_pairs = false;
  o.exposed_area = false;
  return o;
}

// Two unit squares facing each other `gap` apart, and a third square 100 units away that
// only makes the scene large (a diagonal of ~100).
Scene FacingSquaresInALargeScene(double gap) {
  int next = 1;
  std::string obj;
  obj += ObjQuad("lower", "white", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, next);
  obj += ObjQuad("upper", "white", {{0, 0, gap}, {0, 1, gap}, {1, 1, gap}, {1, 0, gap}}, next);
  obj += ObjQuad("far", "white", {{100, 0, 0}, {100, 1, 0}, {100, 1, 1}, {100, 0, 1}}, next);
  return SceneFromObj(obj);
}

// A unit cube, faces inwards, turned about the axis (1, 2, 3) so that no face lies along an
// axis (a face along one keeps its exact coordinate in float, so rounding never moves an
// origin behind it), with its corner at `at`.
Scene TurnedClosedCubeAt(const Vec3& at) {
  const Vec3 axis = Normalize(Vec3{1, 2, 3});
  const double c = std::cos(0.7), s = std::sin(0.7);
  const auto v = [&](double x, double y, double z) {  // Rodrigues' rotation, then the shift
    const Vec3 p{x, y, z};
    return at + p * c + Cross(axis, p) * s + axis * (Dot(axis, p) * (1 - c));
  };
  int next = 1;
  std::string obj;
  obj += ObjQuad("z0", "white", {v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0)}, next);
  obj += ObjQuad("z1", "white", {v(0, 0, 1), v(0, 1, 1), v(1, 1, 1), v(1, 0, 1)}, next);
  obj += ObjQuad("x0", "white", {v(0, 0, 0), v(0, 1, 0), v(0, 1, 1), v(0, 0, 1)}, next);
  obj += ObjQuad("x1", "white", {v(1, 0, 0), v(1, 0, 1), v(1, 1, 1), v(1, 1, 0)}, next);
  obj += ObjQuad("y0", "white", {v(0, 0, 0), v(0, 0, 1), v(1, 0, 1), v(1, 0, 0)}, next);
  obj += ObjQuad("y1", "white", {v(0, 1, 0), v(1, 1, 0), v(1, 1, 1), v(0, 1, 1)}, next);
  return SceneFromObj(obj);
}

// Faces 2e-4 apart in a scene 100 across: a lift of 1e-5 of the diagonal (1e-3, the rule
// before) put every origin past the other face, and F read 0. The conference room's pendant
// lamps touch and nearly touch like this (RESULTS: their rows lost 12.1% of the light at the
// old lift, 11.3% at this one).
TEST(RayLift, AFaceAHairsBreadthAwayIsMet) {
  const double gap = 2e-4;
  RowFixture fixture(FacingSquaresInALargeScene(gap), MeshOptions{0, 0.25});
  ASSERT_LT(RayEpsilonFor(fixture.mesh), gap / 4);
  const CsrMatrix f = fixture.Rows(CountedRows());
  const double exact = testing::ParallelRectangles(1, 1, gap);
  for (const char* from : {"lower", "upper"}) {
    const char* to = std::string(from) == "lower" ? "upper" : "lower";
    const double read = fixture.SurfaceFormFactor(f, from, to);
    std::printf("  F %s -> %s = %.5f (closed form %.5f)\n", from, to, read, exact);
    // 16 patches x 1024 rays: the count's sd is under 1e-3 here.
    EXPECT_NEAR(read, exact, 3e-3) << from;
  }
}

// A closed cube thousands of units from the origin, where a float's spacing is ~2.4e-4 of the
// cube's side: every ray should meet a front side, so the rows' sums fall short of 1 only by
// the rays that slip between two triangles at an edge in single precision (~1e-4 of them
// here, at any lift). A lift below the rounding of the origins puts origins behind their own
// faces, and their rays meet the faces' backs: at a twentieth of a float's spacing, ~40%.
TEST(RayLift, RaysFarFromTheOriginMissTheirOwnFace) {
  RowFixture fixture(TurnedClosedCubeAt({3000.5, -2500.25, 4000.75}), MeshOptions{6 * 64, 0});
  const CsrMatrix f = fixture.Rows(CountedRows());
  double lost = 0;
  for (uint32_t i = 0; i < f.rows; ++i) lost += 1 - f.RowSum(i);
  const double share = lost / f.rows;
  std::printf("  %u rows of 1024 rays: %.0f rays lost, %.2e of them\n", f.rows, lost * 1024, share);
  EXPECT_LT(share, 5e-3);
}

}  // namespace
}  // namespace radflux
