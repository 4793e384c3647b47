#include "solver/scene/gltf_primitive.h"

#include "tiny_gltf.h"

namespace radflux {

bool IsSurfaceMode(int mode) {
  return mode == -1 || mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

size_t TriangleCount(int mode, size_t count) {
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    return count < 3 ? 0 : count - 2;
  }
  return count / 3;
}

std::vector<Triangle> AssembleTriangles(int mode, const std::vector<uint32_t>& indices) {
  std::vector<Triangle> triangles;
  triangles.reserve(TriangleCount(mode, indices.size()));
  const size_t n = indices.size();
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t i = 0; i + 2 < n; ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        triangles.push_back({indices[i + 1], indices[i + 2], indices[0]});
      } else {
        const size_t odd = i % 2;
        triangles.push_back({indices[i], indices[i + 1 + odd], indices[i + 2 - odd]});
      }
    }
    return triangles;
  }
  for (size_t i = 0; i + 2 < n; i += 3) {
    triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
  }
  return triangles;
}

}  // namespace radflux
