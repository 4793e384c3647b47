// Small scenes and helpers shared by the unit tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "solver/formfactor/row_builder.h"
#include "solver/formfactor/row_context.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/scene/obj_loader.h"

namespace radflux::testing {

// MTL with a grey reflector "white" (rho 0.5) and an emitter "lamp" (rho 0.5, Ke 1).
inline const char* kTestMtl =
    "newmtl white\nKd 0.5 0.5 0.5\n"
    "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n"
    "newmtl black\nKd 0 0 0\nKe 1 1 1\n";

inline Scene SceneFromObj(const std::string& obj, const std::string& mtl = kTestMtl) {
  absl::StatusOr<Scene> scene = LoadObjText(obj, mtl, "test.obj");
  EXPECT_TRUE(scene.ok()) << scene.status();
  return scene.ok() ? *scene : Scene{};
}

// An OBJ quad face with vertices listed counter-clockwise seen from the front.
inline std::string ObjQuad(const std::string& object, const std::string& material,
                           const std::vector<Vec3>& v, int& next_index) {
  std::string s = "o " + object + "\nusemtl " + material + "\n";
  for (const Vec3& p : v) {
    s += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  }
  s += "f";
  for (size_t k = 0; k < v.size(); ++k) s += " " + std::to_string(next_index++);
  return s + "\n";
}

// A g x g grid of quad faces of `material` on the parallelogram origin + a ex + b ey, (a, b)
// in [0, 1]^2, front side ex x ey.
inline std::string QuadGrid(const std::string& object, const std::string& material,
                            const Vec3& origin, const Vec3& ex, const Vec3& ey, int g, int& next) {
  std::string obj;
  for (int a = 0; a < g; ++a) {
    for (int b = 0; b < g; ++b) {
      const Vec3 p = origin + ex * (double(a) / g) + ey * (double(b) / g);
      obj += ObjQuad(object, material, {p, p + ex / g, p + ex / g + ey / g, p + ey / g}, next);
    }
  }
  return obj;
}

// The closed unit cube [0, 1]^3 seen from inside (every face facing in), one quad per face,
// object "cube", with materials for the faces z = 0, y = 0, x = 1, y = 1, x = 0, z = 1: as
// OBJ text (vertices numbered from next_index on), and as a scene.
inline std::string InwardUnitCubeObj(const std::array<const char*, 6>& material, int& next_index) {
  const Vec3 v0{0, 0, 0}, v1{1, 0, 0}, v2{1, 1, 0}, v3{0, 1, 0};
  const Vec3 v4{0, 0, 1}, v5{1, 0, 1}, v6{1, 1, 1}, v7{0, 1, 1};
  int& next = next_index;
  std::string obj = ObjQuad("cube", material[0], {v0, v1, v2, v3}, next);
  obj += ObjQuad("cube", material[1], {v0, v4, v5, v1}, next);
  obj += ObjQuad("cube", material[2], {v1, v5, v6, v2}, next);
  obj += ObjQuad("cube", material[3], {v2, v6, v7, v3}, next);
  obj += ObjQuad("cube", material[4], {v3, v7, v4, v0}, next);
  return obj + ObjQuad("cube", material[5], {v4, v7, v6, v5}, next);
}
inline Scene InwardUnitCube(const std::array<const char*, 6>& material,
                            const std::string& mtl = kTestMtl) {
  int next = 1;
  return SceneFromObj(InwardUnitCubeObj(material, next), mtl);
}

// The parallelogram corner + [0,1] u + [0,1] v as m x m cells of two triangles each (OBJ
// faces, counter-clockwise seen from the side u x v points to).
inline std::string TessellatedQuad(const std::string& object, const std::string& material,
                                   const Vec3& corner, const Vec3& u, const Vec3& v, int m,
                                   int& next) {
  std::string s = "o " + object + "\nusemtl " + material + "\n";
  auto vertex = [&](int i, int j) {
    const Vec3 p = corner + u * (double(i) / m) + v * (double(j) / m);
    s += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1);
      const int a = next;
      s += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 2) +
           "\nf " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) +
           "\n";
      next += 4;
    }
  }
  return s;
}

// The mean of a quantity measured once for each seed 1..seeds, and its standard error.
struct SeedMean {
  double mean = 0, standard_error = 0;
};
template <class Measure>  // double(uint64_t seed)
SeedMean MeanOverSeeds(int seeds, Measure measure) {
  double sum = 0, sum2 = 0;
  for (int s = 1; s <= seeds; ++s) {
    const double v = measure(static_cast<uint64_t>(s));
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / seeds;
  return {mean, std::sqrt(std::max(0.0, sum2 / seeds - mean * mean) / (seeds - 1))};
}

// A scene ready for row building: mesh, attributes, Embree, context.
struct RowFixture {
  Scene scene;
  PatchMesh mesh;
  PatchAttributes attributes;
  std::unique_ptr<EmbreeRayCaster> caster;
  RowContext context;

  RowFixture(Scene s, const MeshOptions& options) : scene(std::move(s)) {
    mesh = *SubdivideScene(scene, options);
    attributes = ComputePatchAttributes(scene, mesh);
    caster = *EmbreeRayCaster::Create(mesh);
    context = MakeRowContext(mesh, attributes, *caster);
  }

  CsrMatrix Rows(const FormFactorOptions& options) {
    absl::StatusOr<FormFactorResult> result = BuildFormFactors(context, options);
    EXPECT_TRUE(result.ok()) << result.status();
    return result.ok() ? std::move(result->matrix) : CsrMatrix{};
  }

  // Area-weighted form factor from every patch of object `from` to every patch of `to`.
  double SurfaceFormFactor(const CsrMatrix& f, const std::string& from, const std::string& to) {
    double area = 0, sum = 0;
    for (uint32_t i = 0; i < mesh.size(); ++i) {
      if (ObjectOf(i) != from) continue;
      area += mesh.patches[i].area;
      const auto cols = f.RowCols(i);
      const auto vals = f.RowValues(i);
      for (size_t k = 0; k < cols.size(); ++k) {
        if (ObjectOf(cols[k]) == to) sum += mesh.patches[i].area * vals[k];
      }
    }
    return sum / area;
  }

  const std::string& ObjectOf(uint32_t patch) const {
    return scene.objects[scene.faces[mesh.patches[patch].face].object];
  }
};

}  // namespace radflux::testing
