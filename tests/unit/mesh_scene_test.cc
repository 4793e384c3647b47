// SceneFromMesh: the Scene of a structured mesh is the Scene the OBJ loader makes of the
// same surfaces, and every malformed input is refused naming the face and what is wrong.
#include "solver/scene/mesh_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "solver/scene/obj_loader.h"

namespace radflux {
namespace {

const char* kObj =
    "o lamp\ng top\nusemtl lamp\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
    "o wall\ng side\nusemtl wall\nv 0 0 1\nv 1 0 1\nv 1 1 1\nf 5 7 6\n";
const char* kMtl = "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 2 3\nnewmtl wall\nKd 0.75 0.625 0.5\n";

// The same two faces as kObj + kMtl, as a MeshInput.
MeshInput TwoFaces() {
  MeshInput mesh;
  mesh.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1};
  mesh.faces.push_back({{0, 1, 2, 3}, 0, "lamp", "top"});
  mesh.faces.push_back({{4, 6, 5}, 1, "wall", "side"});
  mesh.materials.push_back({"lamp", {0.5, 0.5, 0.5}, {1, 2, 3}});
  mesh.materials.push_back({"wall", {0.75, 0.625, 0.5}, {0, 0, 0}});
  return mesh;
}

TEST(SceneFromMesh, EqualsTheObjLoadersSceneOfTheSameSurfaces) {
  absl::StatusOr<Scene> obj = LoadObjText(kObj, kMtl, "two.obj");
  ASSERT_TRUE(obj.ok()) << obj.status();
  MeshInput input = TwoFaces();
  // tinyobjloader's decimal parsing is not always correctly rounded (Kd 0.625 is not
  // exactly 0.625): the reflectance is taken as it parsed.
  for (size_t m = 0; m < input.materials.size(); ++m) {
    input.materials[m].reflectance = obj->materials[m].reflectance;
  }
  absl::StatusOr<Scene> mesh = SceneFromMesh(input, "two");
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  ASSERT_EQ(mesh->positions.size(), obj->positions.size());
  for (size_t v = 0; v < obj->positions.size(); ++v) {
    EXPECT_EQ(mesh->positions[v].x, obj->positions[v].x);
    EXPECT_EQ(mesh->positions[v].y, obj->positions[v].y);
    EXPECT_EQ(mesh->positions[v].z, obj->positions[v].z);
  }
  ASSERT_EQ(mesh->faces.size(), obj->faces.size());
  for (size_t f = 0; f < obj->faces.size(); ++f) {
    EXPECT_EQ(mesh->faces[f].vertices, obj->faces[f].vertices);
    EXPECT_EQ(mesh->faces[f].material, obj->faces[f].material);
    EXPECT_EQ(mesh->objects[mesh->faces[f].object], obj->objects[obj->faces[f].object]);
    EXPECT_EQ(mesh->groups[mesh->faces[f].group], obj->groups[obj->faces[f].group]);
  }
  ASSERT_EQ(mesh->materials.size(), obj->materials.size());
  for (size_t m = 0; m < obj->materials.size(); ++m) {
    EXPECT_EQ(mesh->materials[m].name, obj->materials[m].name);
    EXPECT_EQ(mesh->materials[m].reflectance, obj->materials[m].reflectance);
    EXPECT_EQ(mesh->materials[m].emission, obj->materials[m].emission) << "E = pi * L_e";
  }
  EXPECT_EQ(mesh->materials[0].emission[1], 2 * std::numbers::pi);
  EXPECT_EQ(mesh->materials[1].opacity, 1) << "opaque unless given";
}

TEST(SceneFromMesh, KeepsAMaterialsOpacity) {
  MeshInput input = TwoFaces();
  input.materials[1].opacity = 0.375;
  absl::StatusOr<Scene> mesh = SceneFromMesh(input, "two");
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->materials[0].opacity, 1);
  EXPECT_EQ(mesh->materials[1].opacity, 0.375);
}

TEST(SceneFromMesh, RefusesMalformedInputNamingTheFace) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto message = [](const MeshInput& mesh) {
    absl::StatusOr<Scene> scene = SceneFromMesh(mesh, "m");
    EXPECT_EQ(scene.status().code(), absl::StatusCode::kInvalidArgument);
    return std::string(scene.status().message());
  };
  MeshInput m = TwoFaces();
  m.faces[1].vertices.pop_back();
  EXPECT_EQ(message(m), "m: face 1: has 2 vertices; a face needs at least 3");
  m = TwoFaces();
  m.faces[0].vertices[3] = 7;
  EXPECT_EQ(message(m), "m: face 0: vertex index 7 is out of range (the mesh has 7 vertices)");
  m = TwoFaces();
  m.faces[1].material = 2;
  EXPECT_EQ(message(m), "m: face 1: unknown material index 2 (the mesh has 2 materials)");
  m = TwoFaces();
  m.positions[3 * 5 + 2] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(message(m), "m: face 1: vertex 5 has a NaN or infinite coordinate");
  m = TwoFaces();
  m.materials[1].reflectance[2] = nan;
  EXPECT_EQ(message(m), "m: material 1 'wall': reflectance is NaN or infinite");
  m = TwoFaces();
  m.materials[0].emitted_radiance[0] = nan;
  EXPECT_EQ(message(m), "m: material 0 'lamp': emitted radiance is NaN or infinite");
  for (double opacity : {0.0, -0.5, 1.5, nan}) {
    m = TwoFaces();
    m.materials[1].opacity = opacity;
    EXPECT_EQ(message(m), "m: material 1 'wall': opacity " + absl::StrCat(opacity) +
                              " is outside (0, 1]");
  }
  m = TwoFaces();
  m.positions.pop_back();
  EXPECT_EQ(message(m), "m: 20 position values are not x y z triples");
}

}  // namespace
}  // namespace radflux
