// The default view's rule (solver/output/default_view.h) on the Cornell box (open at the
// front) and on the conference room of ../shared/scenes (an interior): the picture
// shows the scene. Every patch is given B = 1, so a pixel is lit exactly when its ray
// meets the front of a patch: black means background or the back of a wall. And on open
// RenderPark scenes, solved: the default picture shows what is lit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "solver/mesh/subdivide.h"
#include "solver/output/default_view.h"
#include "solver/output/render.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/scene/load_scene.h"
#include "tests/source_path.h"
#include "tests/unit/cornell_picture.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

struct Coverage {
  double lit = 0;     // fraction of all pixels lit
  double border = 0;  // fraction of the outermost rows' and columns' pixels lit
};

struct Viewed {
  PatchMesh mesh;
  Camera camera;
  Coverage coverage;
  Vec3 lo, hi;  // the mesh's bounding box
};

Viewed ViewDefault(const std::string& path, const ImportOptions& import, int64_t patches) {
  Viewed v;
  absl::StatusOr<Scene> scene = LoadScene(path, import);
  EXPECT_TRUE(scene.ok()) << scene.status();
  if (!scene.ok()) return v;
  MeshOptions options;
  options.target_patches = patches;
  v.mesh = *SubdivideScene(*scene, options);
  auto caster = EmbreeRayCaster::Create(v.mesh);
  EXPECT_TRUE(caster.ok());
  Camera request;
  request.width = request.height = 64;
  request.vertical_fov_degrees = 39.3077;  // the CLI's default
  v.camera = DefaultCamera(v.mesh, **caster, std::vector<Rgb>(v.mesh.size(), Rgb{1, 1, 1}), request,
                           Vec3{});
  EXPECT_TRUE(ValidateCamera(v.camera).ok());
  const std::vector<Rgb> ones(v.mesh.positions.size(), Rgb{1, 1, 1});
  auto image = RenderRadiance(v.mesh, **caster, ones, v.camera, {});
  EXPECT_TRUE(image.ok());
  int lit = 0, border = 0, border_lit = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool on = image->Pixel(x, y)[0] > 0;
      lit += on;
      if (x == 0 || y == 0 || x == 63 || y == 63) ++border, border_lit += on;
    }
  }
  v.coverage = {lit / 4096.0, border_lit / double(border)};
  v.lo = v.hi = v.mesh.positions[0];
  for (const Vec3& p : v.mesh.positions) {
    v.lo = {std::min(v.lo.x, p.x), std::min(v.lo.y, p.y), std::min(v.lo.z, p.z)};
    v.hi = {std::max(v.hi.x, p.x), std::max(v.hi.y, p.y), std::max(v.hi.z, p.z)};
  }
  return v;
}

TEST(OutputDefaultView, CornellBoxIsSeenThroughItsOpeningWithNoBlackFrame) {
  const Viewed v = ViewDefault(testing::SourcePath("scenes/cornell_box.obj"), {}, 400);
  EXPECT_EQ(v.camera.up, Vec3(0, 1, 0));
  EXPECT_EQ(v.coverage.lit, 1.0);
  EXPECT_EQ(v.coverage.border, 1.0);
  // In front of the open side (z = 0), looking in along +z, within the box's x and y.
  EXPECT_LT(v.camera.position.z, v.lo.z);
  EXPECT_NEAR(Length(Normalize(v.camera.look_at - v.camera.position) - Vec3(0, 0, 1)), 0, 1e-12);
  for (int i : {0, 1}) {
    EXPECT_GT(v.camera.position[i], v.lo[i]);
    EXPECT_LT(v.camera.position[i], v.hi[i]);
  }
}

TEST(OutputDefaultView, ConferenceRoomIsSeenFromInside) {
  ImportOptions import;
  import.emit = {{ "mesh16_SG", Rgb { 10, 10, 10 } }};
  const Viewed v =
      ViewDefault(testing::SourcePath("../shared/scenes/conference/conference.obj"), import, 1000);
  ASSERT_GT(v.mesh.size(), 300000u);
  EXPECT_EQ(v.camera.up, Vec3(0, 1, 0));
  EXPECT_GE(v.coverage.lit, 0.9);
  EXPECT_GE(v.coverage.border, 0.9);
  for (int i : {0, 1, 2}) {
    EXPECT_GT(v.camera.position[i], v.lo[i]) << i;
    EXPECT_LT(v.camera.position[i], v.hi[i]) << i;
  }
  // Looking horizontally, at 55% of the floor-to-ceiling height.
  EXPECT_EQ(v.camera.look_at.y, v.camera.position.y);
}

std::vector<Rgb> Ones(const PatchMesh& mesh) { return {mesh.size(), Rgb{1, 1, 1}}; }

// A room x in [0, 10], y in [0, 6], z in [0, 3], every wall facing in; with `window`, the
// wall y = 0 has a 2 x 1.5 hole at x in [4, 6], z in [1, 2.5]: one or two of the 16
// horizontal rays from the eye escape through it.
PatchMesh ZUpRoom(bool window) {
  PatchMesh mesh;
  const double x = 10, y = 6, z = 3;
  using output_testing::AddFace;
  AddFace(mesh, {{0, 0, 0}, {x, 0, 0}, {x, y, 0}, {0, y, 0}}, {{0, 1, 2, 3}}, {0, 0, 1});
  AddFace(mesh, {{0, 0, z}, {0, y, z}, {x, y, z}, {x, 0, z}}, {{0, 1, 2, 3}}, {0, 0, -1});
  auto wall_y0 = [&](double x0, double x1, double z0, double z1) {
    AddFace(mesh, {{x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}}, {{0, 1, 2, 3}}, {0, 1, 0});
  };
  if (window) {
    wall_y0(0, x, 0, 1), wall_y0(0, x, 2.5, z), wall_y0(0, 4, 1, 2.5), wall_y0(6, x, 1, 2.5);
  } else {
    wall_y0(0, x, 0, z);
  }
  AddFace(mesh, {{0, y, 0}, {x, y, 0}, {x, y, z}, {0, y, z}}, {{0, 1, 2, 3}}, {0, -1, 0});
  AddFace(mesh, {{0, 0, 0}, {0, y, 0}, {0, y, z}, {0, 0, z}}, {{0, 1, 2, 3}}, {1, 0, 0});
  AddFace(mesh, {{x, 0, 0}, {x, 0, z}, {x, y, z}, {x, y, 0}}, {{0, 1, 2, 3}}, {-1, 0, 0});
  return mesh;
}

TEST(OutputDefaultView, AClosedZUpRoomIsSeenAlongItsLongestAxisAtEyeHeight) {
  // The floor and ceiling (120 of area) outweigh the walls facing along y (60): z is up.
  const PatchMesh mesh = ZUpRoom(false);
  const double x = 10, z = 3;
  auto caster = EmbreeRayCaster::Create(mesh);
  ASSERT_TRUE(caster.ok());
  Camera request;
  request.width = request.height = 32;
  const Camera camera = DefaultCamera(mesh, **caster, Ones(mesh), request, Vec3{});
  EXPECT_EQ(camera.up, Vec3(0, 0, 1));
  EXPECT_NEAR(camera.position.z, 0.55 * z, 1e-5);  // eye height (Embree: floats)
  const Vec3 view = camera.look_at - camera.position;
  EXPECT_NEAR(std::abs(view.x), 1, 1e-12);  // along x, the longest axis
  // From 90% of the way to the wall behind, looking towards the far wall.
  const double behind = view.x > 0 ? camera.position.x : x - camera.position.x;
  EXPECT_LT(behind, 0.2 * x);
  EXPECT_GT(behind, 0);
}

TEST(OutputDefaultView, AWindowIsNotAnOpeningToLookInThrough) {
  const PatchMesh mesh = ZUpRoom(true);
  auto caster = EmbreeRayCaster::Create(mesh);
  ASSERT_TRUE(caster.ok());
  Camera request;
  request.width = request.height = 32;
  const Camera camera = DefaultCamera(mesh, **caster, Ones(mesh), request, Vec3{});
  EXPECT_GT(camera.position.y, 0);  // inside, not outside the window's wall
  EXPECT_NEAR(std::abs((camera.look_at - camera.position).x), 1, 1e-12);
}

TEST(OutputDefaultView, AnOpenSceneIsSeenFromTheSideItsLitFaceFaces) {
  PatchMesh mesh;  // one quad facing -z: nothing encloses any probe point
  output_testing::AddFace(mesh, {{0, 0, 0}, {0, 2, 0}, {4, 2, 0}, {4, 0, 0}}, {{0, 1, 2, 3}},
                          {0, 0, -1});
  auto caster = EmbreeRayCaster::Create(mesh);
  ASSERT_TRUE(caster.ok());
  Camera request;
  request.width = 200, request.height = 100;
  request.vertical_fov_degrees = 90;
  // Up +y given: the first horizontal view, along +z, sees its front straight on, the box
  // fitted: half height max(2/2, 4/2 * 100/200) = 1 at tan(45 degrees) = 1.
  const Camera camera = DefaultCamera(mesh, **caster, Ones(mesh), request, Vec3{0, 1, 0});
  EXPECT_EQ(camera.up, Vec3(0, 1, 0));
  EXPECT_EQ(camera.look_at, Vec3(2, 1, 0));
  EXPECT_NEAR(Length(camera.position - Vec3(2, 1, -1)), 0, 1e-12);
  // Up left to the rule: +z (the quad's area faces along z). The horizontal views see it
  // edge-on, those from above (+30 degrees) its back: it is seen from below, 30 degrees.
  const Camera chosen = DefaultCamera(mesh, **caster, Ones(mesh), request, Vec3{});
  EXPECT_EQ(chosen.up, Vec3(0, 0, 1));
  EXPECT_NEAR(Normalize(chosen.look_at - chosen.position).z, std::sin(std::numbers::pi / 6), 1e-12);
}

// A RenderPark scene solved at the CLI's defaults, through its default camera (80 x 60).
struct SolvedView {
  Camera camera;
  double lit = 0;  // fraction of the picture's pixels with radiance > 0
  Vec3 lo, hi;     // the mesh's bounding box
};

SolvedView SolveAndViewDefault(const std::string& path) {
  SolvedView v;
  const testing::SolvedScene solved = testing::SolveDefaults(LoadScene(path, {}));
  if (solved.vertex_radiosity.empty()) return v;
  const PatchMesh& mesh = solved.job().mesh;
  Camera request;
  request.width = 80, request.height = 60;
  request.vertical_fov_degrees = 39.3077;  // the CLI's default
  v.camera =
      DefaultCamera(mesh, *solved.job().caster, solved.result->solve.radiosity, request, Vec3{});
  v.lit = testing::LitShare(testing::RenderSolved(solved, v.camera));
  v.lo = v.hi = mesh.positions.at(0);
  for (const Vec3& p : mesh.positions) {
    v.lo = {std::min(v.lo.x, p.x), std::min(v.lo.y, p.y), std::min(v.lo.z, p.z)};
    v.hi = {std::max(v.hi.x, p.x), std::max(v.hi.y, p.y), std::max(v.hi.z, p.z)};
  }
  return v;
}

bool OutsideBox(const SolvedView& v) {
  for (int i : {0, 1, 2}) {
    if (v.camera.position[i] < v.lo[i] || v.camera.position[i] > v.hi[i]) return true;
  }
  return false;
}

// A floor with a lamp above it, a ball and a two-sided closed box on it: the dark insides
// of the ball and the box are not rooms (the rule before looked out from inside the ball:
// a black picture). Seen from outside, above the floor, its lit part shows.
TEST(OutputDefaultView, AnOpenFloorSceneIsSeenFromAboveNotFromInsideAClosedSolid) {
  const SolvedView v =
      SolveAndViewDefault(testing::SourcePath("../shared/scenes/renderpark/floor_gloss.mgf"));
  EXPECT_EQ(v.camera.up, Vec3(0, 0, 1));
  EXPECT_TRUE(OutsideBox(v));
  EXPECT_GT(v.camera.position.z, v.lo.z);  // above the floor
  EXPECT_GE(v.lit, 0.2);                   // 27% at this commit
}

// A lone luminaire (lamps inside a housing whose outside nothing lights): the dark inside
// of the housing is not a room; from outside, the lamps show.
TEST(OutputDefaultView, ALoneLuminaireIsSeenFromOutsideWithItsLampsInView) {
  const SolvedView v =
      SolveAndViewDefault(testing::SourcePath("../shared/scenes/renderpark/examp1.mgf"));
  EXPECT_TRUE(OutsideBox(v));
  EXPECT_GE(v.lit, 0.03);  // 3.8% at this commit: the lamps between the vanes
}

}  // namespace
}  // namespace radflux
