// ExposedFraction against areas known in closed form: a 4 x 4 floor with a closed 1 x 1 x 1
// box standing on it (no bottom face) is exposed on 15/16 of its area; the quarter of the
// floor that holds the box on 3/4; the box's footprint on none, a far corner on all of it.
#include <gtest/gtest.h>

#include <string>

#include "solver/hierarchical/exposure.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "test_scenes.h"

namespace radflux {
namespace {

Scene FloorWithBox() {
  int next = 1;
  std::string obj =
      testing::ObjQuad("floor", "white", {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}}, next);
  const std::vector<std::vector<Vec3>> box = {{{1, 1, 1}, {2, 1, 1}, {2, 2, 1}, {1, 2, 1}},
                                              {{1, 1, 0}, {2, 1, 0}, {2, 1, 1}, {1, 1, 1}},
                                              {{2, 2, 0}, {1, 2, 0}, {1, 2, 1}, {2, 2, 1}},
                                              {{1, 2, 0}, {1, 1, 0}, {1, 1, 1}, {1, 2, 1}},
                                              {{2, 1, 0}, {2, 2, 0}, {2, 2, 1}, {2, 1, 1}}};
  // Each face its own object, so that contact meshing (which needs a solid of one object)
  // leaves the floor whole and the buried area is there to find.
  for (size_t k = 0; k < box.size(); ++k) {
    obj += testing::ObjQuad("box" + std::to_string(k), "white", box[k], next);
  }
  return testing::SceneFromObj(obj);
}

TEST(HierarchicalExposure, BuriedFloorAreaIsNotExposed) {
  const Scene scene = FloorWithBox();
  MeshOptions options;
  options.follow_contacts = false;  // the floor whole: its open contact lines would cut it
  const PatchMesh mesh = *SubdivideScene(scene, options);
  const std::unique_ptr<EmbreeRayCaster> caster = *EmbreeRayCaster::Create(mesh);
  ElementTree tree = ElementTree::FromMesh(mesh);
  const uint32_t quarter = tree.Split(0);          // [0,2] x [0,2] holds the box's footprint
  const uint32_t sixteenth = tree.Split(quarter);  // its child 2 is [1,2] x [1,2]
  auto exposed = [&](uint32_t node) {
    return ExposedFraction(tree.nodes[node], mesh, *caster, 256, 7, 1e-6);
  };
  EXPECT_NEAR(exposed(0), 15.0 / 16, 0.02);
  EXPECT_NEAR(exposed(quarter), 0.75, 0.02);
  EXPECT_EQ(exposed(sixteenth + 2), 0.0);
  EXPECT_EQ(exposed(sixteenth), 1.0);                 // [0,1] x [0,1]
  EXPECT_EQ(exposed(quarter + 2), 1.0);               // [2,4] x [2,4]
  EXPECT_EQ(exposed(mesh.face_first_patch[1]), 1.0);  // the box's top
}

}  // namespace
}  // namespace radflux
