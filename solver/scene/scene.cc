#include "solver/scene/scene.h"

#include <string>

namespace radflux {

std::string Scene::DescribeFace(size_t f) const {
  const Face& face = faces[f];
  std::string where = source;
  if (face.source_line > 0) where += ":" + std::to_string(face.source_line);
  where += " (face " + std::to_string(f);
  if (face.object < objects.size() && !objects[face.object].empty()) {
    where += " of object '" + objects[face.object] + "'";
  }
  return where + ")";
}

Vec3 PolygonNewellNormal(const std::vector<Vec3>& polygon) {
  Vec3 n;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    n += Cross(a, b);
  }
  return n;
}

std::vector<Vec3> FacePolygon(const Scene& scene, const Face& face) {
  std::vector<Vec3> polygon;
  polygon.reserve(face.vertices.size());
  for (uint32_t v : face.vertices) polygon.push_back(scene.positions[v]);
  return polygon;
}

}  // namespace radflux
