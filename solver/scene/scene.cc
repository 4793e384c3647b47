#include "solver/scene/scene.h"

#include <string>

#include "absl/strings/str_cat.h"

namespace radflux {

std::string Scene::FaceLocation(size_t f) const {
  const Face& face = faces[f];
  const std::string& file = face.source_file < files.size() ? files[face.source_file] : source;
  return absl::StrCat(file, face.source_line > 0 ? absl::StrCat(":", face.source_line) : "");
}

std::string Scene::DescribeFace(size_t f) const {
  const Face& face = faces[f];
  const bool named = face.object < objects.size() && !objects[face.object].empty();
  return absl::StrCat(FaceLocation(f), " (face ", f,
                      named ? absl::StrCat(" of object '", objects[face.object], "'") : "", ")");
}

uint32_t InternName(std::vector<std::string>& names, std::map<std::string, uint32_t>& index,
                    const std::string& name) {
  auto [it, inserted] = index.try_emplace(name, static_cast<uint32_t>(names.size()));
  if (inserted) names.push_back(name);
  return it->second;
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

void FacePolygonInto(const Scene& scene, const Face& face, std::vector<Vec3>& polygon) {
  polygon.clear();
  for (uint32_t v : face.vertices) polygon.push_back(scene.positions[v]);
}

std::vector<Vec3> FacePolygon(const Scene& scene, const Face& face) {
  std::vector<Vec3> polygon;
  polygon.reserve(face.vertices.size());
  for (uint32_t v : face.vertices) polygon.push_back(scene.positions[v]);
  return polygon;
}

}  // namespace radflux
