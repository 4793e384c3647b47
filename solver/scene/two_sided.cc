#include "solver/scene/two_sided.h"

#include <algorithm>

namespace radflux {

uint64_t AddBackFaces(Scene& scene) {
  const size_t count = scene.faces.size();
  for (size_t f = 0; f < count; ++f) {
    if (!scene.materials[scene.faces[f].material].two_sided) continue;
    Face twin = scene.faces[f];
    std::reverse(twin.vertices.begin(), twin.vertices.end());
    twin.back_face = true;
    scene.faces.push_back(std::move(twin));
  }
  return scene.faces.size() - count;
}

}  // namespace radflux
