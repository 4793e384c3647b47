// Hand-built PatchMeshes and temp paths shared by the output_* tests.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "solver/mesh/patch_mesh.h"
#include "solver/output/shading_mesh.h"

namespace radflux::output_testing {

// Appends one face made of the given patches (vertex indices local to `vertices`).
inline void AddFace(PatchMesh& mesh, const std::vector<Vec3>& vertices,
                    const std::vector<std::array<uint32_t, 4>>& patches, const Vec3& normal) {
  if (mesh.face_first_patch.empty()) {
    mesh.face_first_patch.push_back(0);
    mesh.face_first_vertex.push_back(0);
  }
  const auto base = static_cast<uint32_t>(mesh.positions.size());
  const auto face = static_cast<uint32_t>(mesh.face_first_patch.size() - 1);
  mesh.positions.insert(mesh.positions.end(), vertices.begin(), vertices.end());
  for (const auto& local : patches) {
    Patch patch;
    for (int k = 0; k < 4; ++k) patch.v[k] = base + local[k];
    patch.face = face;
    FinishPatch(mesh.positions, normal, patch);
    mesh.patches.push_back(patch);
  }
  mesh.face_first_patch.push_back(static_cast<uint32_t>(mesh.patches.size()));
  mesh.face_first_vertex.push_back(static_cast<uint32_t>(mesh.positions.size()));
}

// A face in the z = 0 plane facing +z, split into 2x2 quads of unequal size:
// columns x in [0,1], [1,3]; rows y in [0,2], [2,3]. Vertex (i, j) is index 3j + i.
// Patch order: (col 0,row 0), (col 1,row 0), (col 0,row 1), (col 1,row 1); areas 2, 4, 1, 2.
inline void AddGridFace(PatchMesh& mesh) {
  const double xs[3] = {0, 1, 3}, ys[3] = {0, 2, 3};
  std::vector<Vec3> v;
  for (double y : ys) {
    for (double x : xs) v.push_back({x, y, 0});
  }
  std::vector<std::array<uint32_t, 4>> patches;
  for (uint32_t j = 0; j < 2; ++j) {
    for (uint32_t i = 0; i < 2; ++i) {
      const uint32_t a = 3 * j + i;
      patches.push_back({a, a + 1, a + 4, a + 3});
    }
  }
  AddFace(mesh, v, patches, {0, 0, 1});
}

// A face [x0, x1] x [y0, y1] in the z = 0 plane facing +z, split into nx x ny equal quads
// (vertex (i, j) is the face's local index j (nx + 1) + i).
inline void AddQuadGridFace(PatchMesh& mesh, double x0, double x1, int nx, double y0, double y1,
                            int ny) {
  std::vector<Vec3> v;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i)
      v.push_back({x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny, 0});
  }
  std::vector<std::array<uint32_t, 4>> patches;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const auto a = static_cast<uint32_t>(j * (nx + 1) + i), row = static_cast<uint32_t>(nx + 1);
      patches.push_back({a, a + 1, a + 1 + row, a + row});
    }
  }
  AddFace(mesh, v, patches, {0, 0, 1});
}

// A flat wall of three faces with T-junctions where they meet: A = [0,2]x[0,1] as 2x3
// quads, B = [2,3]x[0,0.5] and C = [2,3]x[0.5,1] as 1x2 quads each. A's edge x = 2 has
// vertices at y = 1/3, 2/3; B's and C's at y = 0.25, 0.5, 0.75.
inline void AddTJunctionWall(PatchMesh& mesh) {
  AddQuadGridFace(mesh, 0, 2, 2, 0, 1, 3);
  AddQuadGridFace(mesh, 2, 3, 1, 0, 0.5, 2);
  AddQuadGridFace(mesh, 2, 3, 1, 0.5, 1, 2);
}

// A triangle face (0,0,1), (0,2,1), (0,0,3) in the plane x = 0, facing +x.
inline void AddTriangleFace(PatchMesh& mesh) {
  AddFace(mesh, {{0, 0, 1}, {0, 2, 1}, {0, 0, 3}}, {{0, 1, 2, 2}}, {1, 0, 0});
}

// The shading mesh of `mesh` with every face of one material and the default options.
inline ShadingMesh ShadeOneMaterial(const PatchMesh& mesh) {
  const size_t faces = mesh.face_first_patch.empty() ? 0 : mesh.face_first_patch.size() - 1;
  auto shading = BuildShadingMesh(mesh, std::vector<uint32_t>(faces, 0));
  EXPECT_TRUE(shading.ok()) << shading.status();
  return shading.ok() ? *shading : ShadingMesh{};
}

// A fresh path in the test's temporary directory.
inline std::string TempPath(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "radflux_output_tests";
  std::filesystem::create_directories(dir);
  return (dir / (std::string(info->test_suite_name()) + "_" + info->name() + "_" + name)).string();
}

}  // namespace radflux::output_testing
