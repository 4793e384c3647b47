// A fluorescent tube in its housing, as in RenderPark's classroom (issue 21): a two-sided
// tube 1.8 cm under the inside of an open trough whose walls are two two-sided shells 2 mm
// apart, hung 2 cm under the ceiling of a closed room. In a closed room of one reflectance
// rho the power is exact, sum A B = sum A E / (1 - rho), whatever the geometry: the mesher
// must not open holes in the shells (contact_footprints.h), and face grouping must keep the
// light the trough's inside reflects onto itself (face_grouping.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "solver/pipeline.h"
#include "solver/scene/two_sided.h"
#include "solver/solve/energy_balance.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

using testing::SceneFromObj;
using testing::TessellatedQuad;

constexpr double kRho = 0.5;

// rho 0.5 everywhere; every face two-sided (twins added below), as MGF's surfaces are.
const char* kHousingMtl =
    "newmtl white\nKd 0.5 0.5 0.5\n"
    "newmtl dark\nKd 0 0 0\n"
    "newmtl housing\nKd 0.5 0.5 0.5\n"
    "newmtl tube\nKd 0.5 0.5 0.5\nKe 1 1 1\n";

// The box [lo, hi] without its bottom, five faces (two triangles each) facing out of it, or
// into it.
std::string OpenBox(const std::string& object, const Vec3& lo, const Vec3& hi, bool out,
                    int& next) {
  const Vec3 dx{hi.x - lo.x, 0, 0}, dy{0, hi.y - lo.y, 0}, dz{0, 0, hi.z - lo.z};
  // Each face as (corner, u, v) with u x v pointing out; swapped to point in.
  const auto face = [&](const Vec3& corner, const Vec3& u, const Vec3& v) {
    return out ? TessellatedQuad(object, "housing", corner, u, v, 1, next)
               : TessellatedQuad(object, "housing", corner, v, u, 1, next);
  };
  std::string s = face({lo.x, lo.y, hi.z}, dx, dy);  // top
  s += face(lo, dx, dz);                             // side y = lo.y
  s += face({lo.x, hi.y, lo.z}, dz, dx);             // side y = hi.y
  s += face(lo, dz, dy);                             // end x = lo.x
  s += face({hi.x, lo.y, lo.z}, dy, dz);             // end x = hi.x
  return s;
}

// The room [0,4] x [0,3] x [0,3] seen from inside, its floor and walls of `room` (the
// ceiling white) (m x m cells a wall, the ceiling 2 x 2: its
// outward twin's triangles lie 2 cm above the housing, within 2% of their size, 2.4 cm, but
// 4 cm above the tube); the housing, 1.2 x
// 0.16 x 0.08, its top 2 cm under the ceiling, two shells 2 mm apart open below; the tube,
// 1.1 x 0.04 at z = 2.96, Ke 1 on both sides.
Scene RoomWithLampHousing(int m, const std::string& room = "white") {
  int next = 1;
  std::string obj;
  obj += TessellatedQuad("floor", room, {0, 0, 0}, {4, 0, 0}, {0, 3, 0}, m, next);
  obj += TessellatedQuad("ceiling", "white", {0, 0, 3}, {0, 3, 0}, {4, 0, 0}, 2, next);
  obj += TessellatedQuad("wall_y0", room, {0, 0, 0}, {0, 0, 3}, {4, 0, 0}, m, next);
  obj += TessellatedQuad("wall_y3", room, {0, 3, 0}, {4, 0, 0}, {0, 0, 3}, m, next);
  obj += TessellatedQuad("wall_x0", room, {0, 0, 0}, {0, 3, 0}, {0, 0, 3}, m, next);
  obj += TessellatedQuad("wall_x4", room, {4, 0, 0}, {0, 0, 3}, {0, 3, 0}, m, next);
  const double t = 0.002;
  obj += OpenBox("housing", {1.4, 1.42, 2.9}, {2.6, 1.58, 2.98}, true, next);
  obj += OpenBox("housing", {1.4 + t, 1.42 + t, 2.9}, {2.6 - t, 1.58 - t, 2.98 - t}, false, next);
  obj += TessellatedQuad("tube", "tube", {1.45, 1.48, 2.96}, {1.1, 0, 0}, {0, 0.04, 0}, 1, next);
  Scene scene = SceneFromObj(obj, kHousingMtl);
  for (Material& material : scene.materials) material.two_sided = true;
  AddBackFaces(scene);
  return scene;
}

struct Power {
  double emitted = 0;  // sum A E (band 0)
  double total = 0;    // sum A B over the patches (band 0)
};

Power PowerOf(const JobResult& result) {
  const PreparedJob& job = *result.job;
  Power p;
  for (uint32_t u = 0; u < job.Unknowns(); ++u) {
    p.emitted += job.attributes.area[u] * job.attributes.emission[u][0];
  }
  for (uint32_t k = 0; k < job.mesh.size(); ++k) {
    p.total += job.mesh.patches[k].area * result.solve.radiosity[k][0];
  }
  return p;
}

JobOptions Options(bool group, int patches) {
  JobOptions options;
  options.mesh.target_patches = patches;
  options.mesh.group_faces = group;
  options.form_factors.rays = 1024;
  options.form_factors.samples = 16;
  options.solver.tolerance = 1e-6;
  return options;
}

// The energy balance of the solved system (grouped: of the unknowns).
EnergyBalance BalanceOf(const JobResult& result, const JobOptions& options) {
  if (result.solved_balance.has_value()) return **result.solved_balance;
  return ComputeEnergyBalance(
      result.System(), result.solve.radiosity,
      {SampledRays(options.form_factors), LightSamplesPerRow(options.form_factors)});
}

// Without grouping every face is a receiver of contacts: each shell lies 2 mm in front of
// the other's inner side, its back to it, and the ceiling's outward twin 2 cm above the
// housing's top; each hid what lay under it, which left holes (the ray casters see through a
// two-sided face's back where its twin was left out). The tube's upper side, under the
// housing's top and above the bottom of its sides, sees the housing's inside only: no entry
// of its rows reaches the room, nor any of the room's rows it (the ceiling saw it through the
// holes: sum A_i F_ij over the room's rows was 0.97 of its area, the power 24.6% high and the
// balance 24.6% off).
TEST(LampHousing, ShellsHidingEachOtherLeaveNoHole) {
  const JobOptions options = Options(false, 4000);
  absl::StatusOr<JobResult> result = RunJob(RoomWithLampHousing(12), options);
  ASSERT_TRUE(result.ok()) << result.status();
  const PreparedJob& job = *result->job;
  ASSERT_TRUE(job.clusters.empty());
  const auto object = [&](uint32_t p) {
    return job.scene.objects[job.scene.faces[job.mesh.patches[p].face].object];
  };
  const auto tube_top = [&](uint32_t p) {
    return object(p) == "tube" && job.mesh.patches[p].normal.z > 0;
  };
  const auto room = [&](uint32_t p) { return object(p) != "tube" && object(p) != "housing"; };
  double top_area = 0, top_to_room = 0, room_to_top = 0;
  const CsrMatrix& f = result->form_factors;
  for (uint32_t i = 0; i < f.rows; ++i) {
    if (tube_top(i)) top_area += job.attributes.area[i];
    for (size_t k = 0; k < f.RowCols(i).size(); ++k) {
      const uint32_t j = f.RowCols(i)[k];
      const double power = job.attributes.area[i] * f.RowValues(i)[k];  // A_i F_ij
      if (tube_top(i) && room(j)) top_to_room += power;
      if (room(i) && tube_top(j)) room_to_top += power;
    }
  }
  EXPECT_NEAR(top_area, 1.1 * 0.04, 1e-9);
  EXPECT_EQ(top_to_room, 0) << "F from the tube's top to the room " << top_to_room / top_area;
  EXPECT_EQ(room_to_top, 0) << "sum A_i F_ij from the room to the tube's top / its area "
                            << room_to_top / top_area;
  const Power p = PowerOf(*result);
  EXPECT_NEAR(p.total / (p.emitted / (1 - kRho)), 1.0, 0.005);
  const EnergyBalance balance = BalanceOf(*result, options);
  EXPECT_TRUE(balance.Ok()) << balance.OffMessage();
}

// Grouped, the trough's inside is a few groups that are not flat: a group's rays that land on
// the group itself must stay in its row (F_ii: Galerkin's diagonal), or the light the inside
// reflects onto itself leaves the room (the power was 2.1% low). The balance holds with the
// diagonal in the rows. (The tube still sees its groups' average, dimmer than the inside
// alone: its mean B is 4.3% below the ungrouped solve's; face_grouping.h.)
TEST(LampHousing, GroupedInsideKeepsTheLightItReflectsOntoItself) {
  const JobOptions options = Options(true, 300);
  absl::StatusOr<JobResult> result = RunJob(RoomWithLampHousing(12), options);
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_EQ(result->job->Unknowns(), 300u);
  const Power p = PowerOf(*result);
  EXPECT_NEAR(p.total / (p.emitted / (1 - kRho)), 1.0, 0.005);
  const EnergyBalance balance = BalanceOf(*result, options);
  EXPECT_TRUE(balance.Ok()) << balance.OffMessage();
}

// A dark room (floor and walls Kd 0): the light the tube sends out of the trough dies on
// them, so no path of light reaches the white ceiling or the housing's outer side, nor the
// 2 mm cavity between its shells: their exact B is 0, while the trough's inside, lit by the
// tube 2 cm away, is bright. Grouped to 40 unknowns, a group that held inside and outer
// faces of the housing (same object, material and sidedness) gave the outer side and the
// ceiling 2 cm above it the inside's light (RenderPark's classroom: its ceiling +95%); a
// group is of directly lit patches or of unlit ones, never both (direct_lit.h), so they
// read exactly 0.
TEST(LampHousing, GroupedDarkRoomLightsOnlyTheTroughsInside) {
  const JobOptions options = Options(true, 40);
  absl::StatusOr<JobResult> result = RunJob(RoomWithLampHousing(12, "dark"), options);
  ASSERT_TRUE(result.ok()) << result.status();
  const PreparedJob& job = *result->job;
  ASSERT_FALSE(job.clusters.empty());
  const auto object = [&](uint32_t p) {
    return job.scene.objects[job.scene.faces[job.mesh.patches[p].face].object];
  };
  // The trough's inside: the inner shell's faces (centroid on the inner box), facing into it.
  const Vec3 lo{1.402, 1.422, 2.9}, hi{2.598, 1.578, 2.978};
  const auto inside = [&](uint32_t p) {
    const Vec3& c = job.mesh.patches[p].centroid;
    const Vec3 centre = (lo + hi) * 0.5;
    const double tol = 1e-6;
    const bool in_box = c.x > lo.x - tol && c.x < hi.x + tol && c.y > lo.y - tol &&
                        c.y < hi.y + tol && c.z > lo.z - tol && c.z < hi.z + tol;
    const bool on_face = std::abs(c.x - lo.x) < tol || std::abs(c.x - hi.x) < tol ||
                         std::abs(c.y - lo.y) < tol || std::abs(c.y - hi.y) < tol ||
                         std::abs(c.z - hi.z) < tol;
    return in_box && on_face && Dot(job.mesh.patches[p].normal, centre - c) > 0;
  };
  double inside_area = 0, inside_power = 0, outer_max = 0, ceiling_max = 0;
  int outer_patches = 0;
  for (uint32_t p = 0; p < job.mesh.size(); ++p) {
    const double b = std::max({result->solve.radiosity[p][0], result->solve.radiosity[p][1],
                               result->solve.radiosity[p][2]});
    if (object(p) == "ceiling") ceiling_max = std::max(ceiling_max, b);
    if (object(p) != "housing") continue;
    if (inside(p)) {
      inside_area += job.mesh.patches[p].area;
      inside_power += job.mesh.patches[p].area * b;
    } else {
      ++outer_patches;
      outer_max = std::max(outer_max, b);
    }
  }
  // Inside: top, two sides and two ends of the inner box.
  EXPECT_NEAR(inside_area, 2 * (1.196 * 0.078 + 0.156 * 0.078) + 1.196 * 0.156, 1e-9);
  EXPECT_GT(inside_power / inside_area, 0.05);
  EXPECT_GT(outer_patches, 0);
  EXPECT_EQ(outer_max, 0) << "the housing's outer side and cavity";
  EXPECT_EQ(ceiling_max, 0);
}

}  // namespace
}  // namespace radflux
