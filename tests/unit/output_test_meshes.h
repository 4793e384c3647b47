// Hand-built PatchMeshes and temp paths shared by the output_* tests.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "solver/mesh/patch_mesh.h"

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

// A triangle face (0,0,1), (0,2,1), (0,0,3) in the plane x = 0, facing +x.
inline void AddTriangleFace(PatchMesh& mesh) {
  AddFace(mesh, {{0, 0, 1}, {0, 2, 1}, {0, 0, 3}}, {{0, 1, 2, 2}}, {1, 0, 0});
}

// A fresh path in the test's temporary directory.
inline std::string TempPath(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "radflux_output_tests";
  std::filesystem::create_directories(dir);
  return (dir / (std::string(info->test_suite_name()) + "_" + info->name() + "_" + name)).string();
}

}  // namespace radflux::output_testing
