// Slots (contact_footprints.h): an emitting bar lying just in front of a face and facing it
// (the conference room's screen behind the emitting bars of its frame, issue 21) lights the
// narrow strip under it far more than the rest of the face, and the room sees that strip only
// through the slits beside the bar. The face is cut along the bar's outline and the strip is
// kept as hidden patches: unknowns of their own, and no part of the shading of the visible
// patches around them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "solver/mesh/contact_footprints.h"
#include "solver/mesh/face_grouping.h"
#include "solver/mesh/subdivide.h"
#include "solver/output/shading_mesh.h"
#include "solver/output/vertex_radiosity.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

using testing::ObjQuad;
using testing::SceneFromObj;
using testing::TessellatedQuad;

// The bar: y in [kBarLo, kBarHi], z in [1, 9], `gap` in front of the 10 x 10 face x = 0
// (which faces +x), facing -x: two triangles, as a modeller's tessellated rectangle.
constexpr double kBarLo = 4.8, kBarHi = 5.2;
constexpr double kBarArea = (kBarHi - kBarLo) * 8;

// The face (object "face", material `face_material`) is scene face 0; the bar's two
// triangles are faces 1 and 2.
Scene FaceAndBar(const std::string& face_material, const std::string& bar_material, double gap) {
  int next = 1;
  std::string obj =
      ObjQuad("face", face_material, {{0, 0, 0}, {0, 10, 0}, {0, 10, 10}, {0, 0, 10}}, next);
  obj += TessellatedQuad("bar", bar_material, {gap, kBarLo, 1}, {0, 0, 8},
                         {0, kBarHi - kBarLo, 0}, 1, next);
  return SceneFromObj(obj);
}

double PolygonArea(const std::vector<Vec3>& polygon) {
  return Length(PolygonNewellNormal(polygon)) / 2;
}

TEST(EmitterSlot, AnEmitterFacingAFaceCloselyMakesOneSlotOfItsOutline) {
  // The receiver's size is 10, so a slot may be up to 0.2 deep (2% of it; the bar's width,
  // 0.4, is larger).
  const std::vector<FaceContacts> contacts = FindContacts(FaceAndBar("lamp", "lamp", 0.1));
  ASSERT_EQ(contacts[0].slots.size(), 1u) << "the bar's two triangles join into one slot";
  EXPECT_EQ(contacts[0].slots[0].size(), 4u);
  EXPECT_NEAR(PolygonArea(contacts[0].slots[0]), kBarArea, 1e-9);
  EXPECT_TRUE(contacts[0].footprints.empty());
  for (const Vec3& p : contacts[0].slots[0]) EXPECT_NEAR(p.x, 0, 1e-12) << "in the face's plane";
  // Counter-clockwise about the face's normal, as the clipper takes footprints.
  EXPECT_GT(Dot(PolygonNewellNormal(contacts[0].slots[0]), Vec3{1, 0, 0}), 0);
}

TEST(EmitterSlot, NoSlotUnderANonEmitterOrTooFarOff) {
  for (const auto& [bar, gap] : {std::pair<std::string, double>{"white", 0.1}, {"lamp", 0.3}}) {
    const std::vector<FaceContacts> contacts = FindContacts(FaceAndBar("lamp", bar, gap));
    EXPECT_TRUE(contacts[0].empty()) << bar << " at " << gap;
  }
}

TEST(EmitterSlot, ACeilingJustAboveALampsTopDoesNotHideItsLight) {
  // A 10 x 10 two-sided ceiling at z = 3 (face 0 facing down, face 1 its outward twin facing
  // up) and a lamp's top (face 2: 0.4 x 0.4, emitting, facing up) 2 cm under it, as in
  // RenderPark's corridor. The twin lies 2 cm in front of the top with its back to it, 5% of
  // the top's size: the top is not hidden (2% of the ceiling's size, 20 cm, hid it); the
  // ceiling above it is a slot.
  int next = 1;
  std::string obj =
      ObjQuad("ceiling", "white", {{0, 0, 3}, {0, 10, 3}, {10, 10, 3}, {10, 0, 3}}, next);
  obj += ObjQuad("ceiling", "white", {{0, 0, 3}, {10, 0, 3}, {10, 10, 3}, {0, 10, 3}}, next);
  obj += ObjQuad("lamp", "lamp",
                 {{4.8, 4.8, 2.98}, {5.2, 4.8, 2.98}, {5.2, 5.2, 2.98}, {4.8, 5.2, 2.98}}, next);
  const std::vector<FaceContacts> contacts = FindContacts(SceneFromObj(obj));
  EXPECT_TRUE(contacts[2].empty()) << "the lamp's top is not hidden";
  ASSERT_EQ(contacts[0].slots.size(), 1u);
  EXPECT_NEAR(PolygonArea(contacts[0].slots[0]), 0.16, 1e-9);
  EXPECT_TRUE(contacts[1].empty()) << "the outward twin is behind the lamp";
}

PatchMesh UnitPatches(const Scene& scene) {
  MeshOptions options;
  options.max_edge = 1;
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, options);
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  return mesh.ok() ? *std::move(mesh) : PatchMesh{};
}

TEST(EmitterSlot, TheStripUnderTheBarIsKeptAsHiddenPatches) {
  const PatchMesh mesh = UnitPatches(FaceAndBar("lamp", "lamp", 0.1));
  double hidden = 0, face = 0;
  for (const Patch& p : mesh.patches) {
    if (p.face == 0) face += p.area;
    if (p.hidden) {
      EXPECT_EQ(p.face, 0u) << "only the face under the bar has hidden patches";
      EXPECT_GT(p.centroid.y, kBarLo);
      EXPECT_LT(p.centroid.y, kBarHi);
      hidden += p.area;
    }
  }
  EXPECT_NEAR(hidden, kBarArea, 1e-9);
  EXPECT_NEAR(face, 100, 1e-9) << "a slot is kept, not left out";
}

TEST(EmitterSlot, HiddenPatchesAreUnknownsOfTheirOwn) {
  const Scene scene = FaceAndBar("white", "lamp", 0.1);
  const PatchMesh mesh = UnitPatches(scene);
  const PatchClusters clusters = GroupPatches(scene, mesh, 4);
  int hidden = 0;
  size_t largest = 0;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const size_t members = clusters.Members(clusters.of_patch[p]).size();
    largest = std::max(largest, members);
    if (!mesh.patches[p].hidden) continue;
    ++hidden;
    EXPECT_EQ(members, 1u) << "hidden patch " << p;
  }
  EXPECT_GT(hidden, 0);
  EXPECT_GT(largest, 1u) << "the face's other patches are grouped";
}

TEST(EmitterSlot, TheHotStripDoesNotPullUpTheShadingBesideIt) {
  // A constant B on what is seen and a thousand times it in the slot: every vertex of a shown
  // patch reads the constant (a plane fit reproduces a constant exactly), the ones on the
  // slot's outline included.
  const Scene scene = FaceAndBar("lamp", "lamp", 0.1);
  const PatchMesh mesh = UnitPatches(scene);
  absl::StatusOr<ShadingMesh> shading = BuildShadingMesh(mesh, FaceMaterials(scene));
  ASSERT_TRUE(shading.ok()) << shading.status();
  std::vector<Rgb> b(mesh.size());
  for (size_t p = 0; p < mesh.size(); ++p) {
    const double value = mesh.patches[p].hidden ? 1000 : 1;
    b[p] = {value, value, value};
  }
  absl::StatusOr<std::vector<Rgb>> values = VertexRadiosity(mesh, *shading, b);
  ASSERT_TRUE(values.ok()) << values.status();
  int outline = 0;
  for (const Patch& p : mesh.patches) {
    if (p.hidden) continue;
    for (int k = 0; k < p.VertexCount(); ++k) {
      const Vec3& x = mesh.positions[p.v[k]];
      EXPECT_NEAR((*values)[p.v[k]][0], 1, 1e-9) << x.x << " " << x.y << " " << x.z;
      if (p.face == 0 && (std::abs(x.y - kBarLo) < 1e-9 || std::abs(x.y - kBarHi) < 1e-9)) {
        ++outline;
      }
    }
  }
  EXPECT_GT(outline, 0) << "shown patches reach the slot's outline";
}

}  // namespace
}  // namespace radflux
