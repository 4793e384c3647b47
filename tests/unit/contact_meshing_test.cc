// Meshing that follows contact: a closed block resting on a floor cuts the floor's patches
// along its outline and leaves the floor under it out; open or lifted blocks and a room's
// walls standing on the floor do not; a partition's open foot cuts the floor, both sides kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "solver/mesh/contact_clip.h"
#include "solver/mesh/contact_footprints.h"
#include "solver/mesh/subdivide.h"
#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "tests/source_path.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

using testing::ObjQuad;

// A diamond (a square turned 45 degrees, area 18) counter-clockwise seen from above (+y),
// so that it is not aligned with the floor's 1 x 1 patch grid.
const std::vector<Vec3> kDiamond = {{5, 0, 2}, {2, 0, 5}, {5, 0, 8}, {8, 0, 5}};
constexpr double kDiamondArea = 18;

struct BlockShape {
  double lift = 0;  // gap between the floor and the block's foot
  bool lid = true;  // the top face
};

// A 10 x 10 floor at y = 0 facing +y, and a block of height 3 on kDiamond.
std::string FloorAndBlock(const BlockShape& shape, bool room_walls) {
  int next = 1;
  std::string obj =
      ObjQuad("floor", "white", {{0, 0, 0}, {0, 0, 10}, {10, 0, 10}, {10, 0, 0}}, next);
  const Vec3 up{0, 3, 0}, lift{0, shape.lift, 0};
  for (size_t i = 0; i < kDiamond.size(); ++i) {
    const Vec3 a = kDiamond[i] + lift, b = kDiamond[(i + 1) % kDiamond.size()] + lift;
    obj += ObjQuad("block", "white", {a, b, b + up, a + up}, next);  // normal out of the block
  }
  if (shape.lid) {
    std::vector<Vec3> top;
    for (const Vec3& p : kDiamond) top.push_back(p + lift + up);
    obj += ObjQuad("block", "white", top, next);
  }
  if (room_walls) {  // walls around the floor's border, facing into the room
    const std::vector<Vec3> corners = {{0, 0, 0}, {0, 0, 10}, {10, 0, 10}, {10, 0, 0}};
    for (size_t i = 0; i < 4; ++i) {
      const Vec3 a = corners[i], b = corners[(i + 1) % 4], h{0, 5, 0};
      obj += ObjQuad("wall" + std::to_string(i), "white", {b, a, a + h, b + h}, next);
    }
  }
  obj += ObjQuad("lamp", "lamp", {{4, 9, 4}, {6, 9, 4}, {6, 9, 6}, {4, 9, 6}}, next);
  return obj;
}

size_t CountFootprints(const std::vector<FaceContacts>& contacts) {
  size_t n = 0;
  for (const FaceContacts& f : contacts) n += f.footprints.size();
  return n;
}

size_t CountLines(const std::vector<FaceContacts>& contacts) {
  size_t n = 0;
  for (const FaceContacts& f : contacts) n += f.lines.size();
  return n;
}

TEST(ContactFootprints, AClosedBlockOnTheFloorIsOneFootprintOnTheFloorOnly) {
  const Scene scene = testing::SceneFromObj(FloorAndBlock({}, /*room_walls=*/true));
  const std::vector<FaceContacts> contacts = FindContacts(scene);
  ASSERT_EQ(contacts.size(), scene.faces.size());
  ASSERT_EQ(CountFootprints(contacts), 1u);      // the walls' loop faces inwards: not a foot
  ASSERT_EQ(contacts[0].footprints.size(), 1u);  // face 0 is the floor
  // The walls stand on the floor's border and the block's edges are its footprint: no lines.
  EXPECT_EQ(CountLines(contacts), 0u);
  const Footprint& foot = contacts[0].footprints[0];
  ASSERT_EQ(foot.size(), 4u);
  for (const Vec3& corner : kDiamond) {
    EXPECT_TRUE(std::any_of(foot.begin(), foot.end(),
                            [&](const Vec3& p) { return Length(p - corner) < 1e-12; }));
  }
  EXPECT_NEAR(Dot(PolygonNewellNormal(foot), Vec3{0, 1, 0}) / 2, kDiamondArea, 1e-9);
}

// An open tube's foot is no footprint (its inside is lit) but four contact lines; a lifted
// block touches nothing.
TEST(ContactFootprints, AnOpenTubeHasLinesOnlyALiftedBlockNothing) {
  const std::vector<FaceContacts> tube =
      FindContacts(testing::SceneFromObj(FloorAndBlock({.lift = 0, .lid = false}, false)));
  EXPECT_EQ(CountFootprints(tube), 0u);
  EXPECT_EQ(CountLines(tube), 4u);
  EXPECT_EQ(tube[0].lines.size(), 4u);
  // 0.01 is above the tolerance (1e-5 of the diagonal, ~1.4e-4 here).
  const std::vector<FaceContacts> lifted =
      FindContacts(testing::SceneFromObj(FloorAndBlock({.lift = 0.01, .lid = true}, false)));
  EXPECT_EQ(CountFootprints(lifted), 0u);
  EXPECT_EQ(CountLines(lifted), 0u);
}

// Each of the block's four sides stands on the floor by its first edge (a -> b); the lid, the
// walls (on the floor's border) and the floor itself stand on nothing. An open tube's sides
// stand on the floor too, but are no solid's: no feet.
TEST(ContactFootprints, TheBlocksSidesKnowTheirFeet) {
  for (const FaceContacts& c :
       FindContacts(testing::SceneFromObj(FloorAndBlock({.lift = 0, .lid = false}, false)))) {
    EXPECT_TRUE(c.feet.empty());
  }
  const std::vector<FaceContacts> contacts =
      FindContacts(testing::SceneFromObj(FloorAndBlock({}, /*room_walls=*/true)));
  ASSERT_EQ(contacts.size(), 11u);  // floor, 4 sides, lid, 4 walls, lamp
  for (uint32_t f = 1; f <= 4; ++f) EXPECT_EQ(contacts[f].feet, std::vector<int>{0}) << f;
  for (uint32_t f : {0u, 5u, 6u, 7u, 8u, 9u, 10u}) EXPECT_TRUE(contacts[f].feet.empty()) << f;
}

// At a patch edge of 1 the block's sides (3 high, sqrt(18) wide) get a row 1/3 high along
// their foot (kFootStrip), then rows as the edge length asks: their lowest patches end at
// y = 1/3 and the next row's at y = 1/3 + 8/9 (3 rows over the other 8/3). A lifted block's
// sides stand on nothing and keep 3 even rows. With neither a count nor an edge (the
// hierarchical solver's roots) every face stays one patch: no strip of zero height.
TEST(ContactMeshing, ASidesFirstRowIsAStripAlongItsFoot) {
  for (const double lift : {0.0, 0.5}) {
    const Scene scene = testing::SceneFromObj(FloorAndBlock({.lift = lift, .lid = true}, false));
    MeshOptions options;
    options.max_edge = 1;
    absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, options);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    for (uint32_t f = 1; f <= 4; ++f) {
      std::vector<double> heights;  // distinct patch corner heights above the block's foot
      for (uint32_t p = mesh->face_first_patch[f]; p < mesh->face_first_patch[f + 1]; ++p) {
        for (int k = 0; k < mesh->patches[p].VertexCount(); ++k) {
          const double y = mesh->Vertex(p, k).y - lift;
          if (std::none_of(heights.begin(), heights.end(),
                           [&](double h) { return std::abs(h - y) < 1e-9; })) {
            heights.push_back(y);
          }
        }
      }
      std::sort(heights.begin(), heights.end());
      const std::vector<double> expected =
          lift == 0 ? std::vector<double>{0, 1.0 / 3, 1.0 / 3 + 8.0 / 9, 1.0 / 3 + 16.0 / 9, 3}
                    : std::vector<double>{0, 1, 2, 3};
      ASSERT_EQ(heights.size(), expected.size()) << "face " << f << " lift " << lift;
      for (size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(heights[k], expected[k], 1e-9);
    }
  }
  const Scene scene = testing::SceneFromObj(FloorAndBlock({}, false));
  absl::StatusOr<PatchMesh> roots = SubdivideScene(scene, MeshOptions{});
  ASSERT_TRUE(roots.ok()) << roots.status();
  for (uint32_t f = 1; f <= 4; ++f) {
    ASSERT_EQ(roots->face_first_patch[f + 1] - roots->face_first_patch[f], 1u) << f;
    EXPECT_NEAR(roots->patches[roots->face_first_patch[f]].area, 3 * std::sqrt(18.0), 1e-9);
  }
}

// A 10 x 10 ceiling at y = 5 facing down and a 2 x 2 lamp `gap` below it, facing down (its
// back to the ceiling) or up.
Scene CeilingAndLamp(double gap, bool lamp_faces_down) {
  int next = 1;
  std::string obj =
      ObjQuad("ceiling", "white", {{0, 5, 0}, {10, 5, 0}, {10, 5, 10}, {0, 5, 10}}, next);
  const double y = 5 - gap;
  std::vector<Vec3> lamp = {{4, y, 4}, {6, y, 4}, {6, y, 6}, {4, y, 6}};
  if (!lamp_faces_down) std::reverse(lamp.begin(), lamp.end());
  obj += ObjQuad("lamp", "lamp", lamp, next);
  return testing::SceneFromObj(obj);
}

TEST(ContactFootprints, AFaceHungJustBelowACeilingHidesItsOutlineThere) {
  // 0.01 is above the contact tolerance (~1.4e-4) and within 2% of the lamp's size (0.04).
  const std::vector<FaceContacts> contacts = FindContacts(CeilingAndLamp(0.01, true));
  ASSERT_EQ(CountFootprints(contacts), 1u);
  EXPECT_EQ(CountLines(contacts), 0u);
  ASSERT_EQ(contacts[0].footprints.size(), 1u);  // on the ceiling, none on the lamp
  const Footprint& foot = contacts[0].footprints[0];
  for (const Vec3& p : foot) EXPECT_NEAR(p.y, 5, 1e-12);
  // Counter-clockwise about the ceiling's normal (-y), the lamp's area.
  EXPECT_NEAR(Dot(PolygonNewellNormal(foot), Vec3{0, -1, 0}) / 2, 4, 1e-9);
  // Further than 2% of its size below (2.5%), or facing the other way, it hides nothing.
  EXPECT_EQ(CountFootprints(FindContacts(CeilingAndLamp(0.05, true))), 0u);
  EXPECT_EQ(CountFootprints(FindContacts(CeilingAndLamp(0.01, false))), 0u);
}

TEST(ContactMeshing, TheCeilingAboveAHungLampHasNoPatches) {
  const Scene scene = CeilingAndLamp(0.01, true);
  MeshOptions options;
  options.max_edge = 1.5;  // the lamp's edges fall inside patches of the ceiling's grid
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, options);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  double ceiling_area = 0;
  for (uint32_t p = mesh->face_first_patch[0]; p < mesh->face_first_patch[1]; ++p) {
    const Vec3 c = mesh->patches[p].centroid;
    EXPECT_FALSE(c.x > 4 && c.x < 6 && c.z > 4 && c.z < 6) << "patch " << p;
    ceiling_area += mesh->patches[p].area;
  }
  EXPECT_NEAR(ceiling_area, 100 - 4, 1e-9);
}

bool InsideDiamond(const Vec3& p, double margin) {
  for (size_t i = 0; i < kDiamond.size(); ++i) {
    const Vec3& a = kDiamond[i];
    const Vec3& b = kDiamond[(i + 1) % kDiamond.size()];
    if (Dot(Cross(b - a, p - a), Vec3{0, 1, 0}) <= margin) return false;
  }
  return true;
}

TEST(ContactMeshing, FloorPatchesFollowTheBlocksOutlineAndLeaveItsFootOut) {
  const Scene scene = testing::SceneFromObj(FloorAndBlock({}, true));
  MeshOptions options;
  options.max_edge = 1;
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, options);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  double floor_area = 0;
  for (uint32_t p = mesh->face_first_patch[0]; p < mesh->face_first_patch[1]; ++p) {
    const Patch& patch = mesh->patches[p];
    EXPECT_GT(patch.area, 1e-9);
    EXPECT_FALSE(InsideDiamond(patch.centroid, 1e-9)) << "patch " << p;
    // No patch reaches into the foot: every corner is outside or on its outline.
    for (int k = 0; k < patch.VertexCount(); ++k) {
      EXPECT_FALSE(InsideDiamond(mesh->Vertex(p, k), 1e-9)) << "patch " << p << " corner " << k;
    }
    floor_area += patch.area;
  }
  EXPECT_NEAR(floor_area, 100 - kDiamondArea, 1e-9);
  // The face's vertex range is exactly what its patches use.
  std::vector<bool> used(mesh->positions.size(), false);
  for (const Patch& patch : mesh->patches) {
    for (int k = 0; k < patch.VertexCount(); ++k) used[patch.v[k]] = true;
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
  // The diamond's corners are patch corners: the outline is meshed, not approximated.
  for (const Vec3& corner : kDiamond) {
    bool found = false;
    for (uint32_t v = mesh->face_first_vertex[0]; v < mesh->face_first_vertex[1]; ++v) {
      found |= Length(mesh->positions[v] - corner) < 1e-12;
    }
    EXPECT_TRUE(found) << corner.x << " " << corner.z;
  }
}

// A 10 x 10 floor (rho 0.5) split by a zero-thickness black partition 10 high standing on it
// along the open polyline kPartition (two panels, from the floor's near border to its far
// one, not along the floor's 1 x 1 patch grid), and a small black lamp 2 above the floor on
// the -x side, facing down. No light reaches the +x side: a ray from the lamp down to it
// crosses the partition below the lamp's height, the partition and the lamp reflect nothing,
// and floor patches do not see each other. So a floor patch wholly on the +x side has B = 0
// exactly, whatever the sampling; one straddling the foot would take light from its -x part.
const std::vector<Vec3> kPartition = {{5.3, 0, 0}, {4.6, 0, 5.2}, {5.7, 0, 10}};

std::string FloorPartitionAndLamp() {
  int next = 1;
  std::string obj =
      ObjQuad("floor", "white", {{0, 0, 0}, {0, 0, 10}, {10, 0, 10}, {10, 0, 0}}, next);
  const Vec3 up{0, 10, 0};
  for (size_t i = 0; i + 1 < kPartition.size(); ++i) {  // facing the lamp (-x)
    const Vec3 a = kPartition[i], b = kPartition[i + 1];
    obj += ObjQuad("partition", "dark", {b, a, a + up, b + up}, next);
  }
  obj += ObjQuad("lamp", "black", {{1, 2, 4}, {2, 2, 4}, {2, 2, 6}, {1, 2, 6}}, next);
  return obj;
}

// Signed distance of floor point p from the partition's foot, > 0 on the dark (+x) side.
double DarkSide(const Vec3& p) {
  const size_t i = p.z <= kPartition[1].z ? 0 : 1;
  const Vec3 a = kPartition[i], along = Normalize(kPartition[i + 1] - a);
  return Dot(Cross(along, p - a), Vec3{0, 1, 0});
}

TEST(ContactMeshing, FloorPatchesFollowAPartitionsOpenFootAndItsDarkSideGetsNoLight) {
  const std::string mtl = std::string(testing::kTestMtl) + "newmtl dark\nKd 0 0 0\n";
  const Scene scene = testing::SceneFromObj(FloorPartitionAndLamp(), mtl);
  const std::vector<FaceContacts> contacts = FindContacts(scene);
  ASSERT_EQ(CountFootprints(contacts), 0u);
  ASSERT_EQ(contacts[0].lines.size(), 2u);  // the two panels' feet, on the floor only
  EXPECT_EQ(CountLines(contacts), 2u);
  JobOptions options;
  options.mesh.max_edge = 1;
  options.form_factors.rays = 64;
  absl::StatusOr<JobResult> result = RunJob(scene, options);
  ASSERT_TRUE(result.ok()) << result.status();
  const PatchMesh& mesh = result->job->mesh;
  double floor_area = 0;
  int dark = 0, lit = 0;
  for (uint32_t p = mesh.face_first_patch[0]; p < mesh.face_first_patch[1]; ++p) {
    const Patch& patch = mesh.patches[p];
    // No patch crosses the foot: all corners on one side of it (or on it).
    double lo = 0, hi = 0;
    for (int k = 0; k < patch.VertexCount(); ++k) {
      lo = std::min(lo, DarkSide(mesh.Vertex(p, k)));
      hi = std::max(hi, DarkSide(mesh.Vertex(p, k)));
    }
    EXPECT_TRUE(lo > -1e-9 || hi < 1e-9) << "patch " << p << " straddles: " << lo << " " << hi;
    const Rgb& b = result->solve.radiosity[p];
    if (DarkSide(patch.centroid) > 0) {
      EXPECT_EQ(b, (Rgb{0, 0, 0})) << "patch " << p;
      ++dark;
    } else {
      EXPECT_GT(b[0], 0) << "patch " << p;
      ++lit;
    }
    floor_area += patch.area;
  }
  EXPECT_NEAR(floor_area, 100, 1e-9);  // both sides kept
  EXPECT_GT(dark, 40);
  EXPECT_GT(lit, 40);
  // The polyline's corners are patch corners: the foot is meshed, not approximated.
  for (const Vec3& corner : kPartition) {
    bool found = false;
    for (uint32_t v = mesh.face_first_vertex[0]; v < mesh.face_first_vertex[1]; ++v) {
      found |= Length(mesh.positions[v] - corner) < 1e-9;
    }
    EXPECT_TRUE(found) << corner.x << " " << corner.z;
  }
}

// Face f of `mesh` alone, its vertex indices from 0 (ClipFacePatches and ClippedPatchCount
// take the last face meshed).
PatchMesh FaceAlone(const PatchMesh& mesh, uint32_t f) {
  PatchMesh face;
  const uint32_t first_vertex = mesh.face_first_vertex[f];
  face.positions.assign(mesh.positions.begin() + first_vertex,
                        mesh.positions.begin() + mesh.face_first_vertex[f + 1]);
  for (uint32_t p = mesh.face_first_patch[f]; p < mesh.face_first_patch[f + 1]; ++p) {
    Patch patch = mesh.patches[p];
    for (uint32_t& v : patch.v) v -= first_vertex;
    face.patches.push_back(patch);
  }
  return face;
}

// The count the edge length is chosen by is the count the cut faces get: the Cornell box's
// floor (both blocks' footprints, refined beside them) and ceiling (the lamp's outline) at
// several edge lengths, against ClipFacePatches itself.
TEST(ContactMeshing, ClippedPatchCountIsThePatchesTheCutLeaves) {
  absl::StatusOr<Scene> scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok()) << scene.status();
  const std::vector<FaceContacts> contacts = FindContacts(*scene);
  int cut_faces = 0;
  for (double h : {20.0, 37.0, 50.0, 81.0}) {
    MeshOptions options;
    options.max_edge = h;
    options.follow_contacts = false;
    absl::StatusOr<PatchMesh> mesh = SubdivideScene(*scene, options);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    for (uint32_t f = 0; f < scene->faces.size(); ++f) {
      if (contacts[f].empty()) continue;
      PatchMesh face = FaceAlone(*mesh, f);
      const Vec3 normal = face.patches[0].normal;
      const size_t unclipped = face.size();
      const size_t counted = ClippedPatchCount(contacts[f], normal, h, 0, 0, face);
      ClipFacePatches(contacts[f], normal, h, 0, 0, face);
      EXPECT_EQ(counted, face.size()) << "face " << f << " at h = " << h;
      cut_faces += face.size() != unclipped ? 1 : 0;
    }
  }
  EXPECT_GE(cut_faces, 8);  // floor and ceiling at every h
}

}  // namespace
}  // namespace radflux
