#include "solver/scene/duplicate_faces.h"

#include <algorithm>
#include <bit>
#include <tuple>

namespace radflux {
namespace {

bool Less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
}

// Where the canonical cycle of `face` starts: its lexicographically smallest position.
size_t CycleStart(const Scene& scene, const Face& face) {
  size_t start = 0;
  for (size_t k = 1; k < face.vertices.size(); ++k) {
    if (Less(scene.positions[face.vertices[k]], scene.positions[face.vertices[start]])) start = k;
  }
  return start;
}

uint64_t Mix(uint64_t h, double value) {
  h ^= std::bit_cast<uint64_t>(value + 0.0) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  return h;
}

uint64_t CycleHash(const Scene& scene, const Face& face, size_t start) {
  uint64_t h = face.vertices.size();
  for (size_t k = 0; k < face.vertices.size(); ++k) {
    const Vec3& p = scene.positions[face.vertices[(start + k) % face.vertices.size()]];
    h = Mix(Mix(Mix(h, p.x), p.y), p.z);
  }
  return h;
}

bool SameCycle(const Scene& scene, const Face& a, size_t start_a, const Face& b, size_t start_b) {
  const size_t n = a.vertices.size();
  if (b.vertices.size() != n) return false;
  for (size_t k = 0; k < n; ++k) {
    if (!(scene.positions[a.vertices[(start_a + k) % n]] ==
          scene.positions[b.vertices[(start_b + k) % n]])) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::vector<uint32_t> FindDuplicateFaces(const Scene& scene) {
  struct Key {
    uint64_t hash;
    uint32_t face, start;
  };
  std::vector<Key> keys(scene.faces.size());
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    const size_t start = CycleStart(scene, scene.faces[f]);
    keys[f] = {CycleHash(scene, scene.faces[f], start), f, static_cast<uint32_t>(start)};
  }
  std::sort(keys.begin(), keys.end(),
            [](const Key& a, const Key& b) { return std::tie(a.hash, a.face) < std::tie(b.hash, b.face); });
  std::vector<uint32_t> duplicates;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].hash == keys[i].hash) ++j;
    for (size_t b = i + 1; b < j; ++b) {  // compare with each earlier face of equal hash
      for (size_t a = i; a < b; ++a) {
        const Face& fa = scene.faces[keys[a].face];
        const Face& fb = scene.faces[keys[b].face];
        if (SameCycle(scene, fa, keys[a].start, fb, keys[b].start)) {
          duplicates.push_back(keys[b].face);
          break;
        }
      }
    }
    i = j;
  }
  std::sort(duplicates.begin(), duplicates.end());
  return duplicates;
}

}  // namespace radflux
