#include <gtest/gtest.h>

#include <numbers>

#include "solver/scene/obj_loader.h"
#include "solver/scene/validation.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

TEST(ObjLoader, CornellBoxLoadsWithMaterialsAndNames) {
  auto scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_TRUE(ValidateScene(*scene).ok()) << ValidateScene(*scene);
  EXPECT_EQ(scene->faces.size(), 17u);  // 5 walls (red = 2 triangles) + light + 2 x 5 block faces
  bool found_light = false;
  for (size_t f = 0; f < scene->faces.size(); ++f) {
    const Material& m = scene->materials[scene->faces[f].material];
    if (scene->objects[scene->faces[f].object] == "light") {
      found_light = true;
      EXPECT_NEAR(m.emission[0], 17 * std::numbers::pi, 1e-9);
      EXPECT_NEAR(m.emission[2], 4 * std::numbers::pi, 1e-9);
      EXPECT_DOUBLE_EQ(m.reflectance[0], 0.78);
    }
  }
  EXPECT_TRUE(found_light);
}

}  // namespace
}  // namespace radflux
