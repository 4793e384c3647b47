#include "solver/mesh/adaptive_tree.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <unordered_map>

namespace radflux {
namespace {

Vec3 Mid(const Vec3& a, const Vec3& b) { return (a + b) * 0.5; }

double TriangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  return Length(Cross(b - a, c - a)) / 2;
}

void FinishElement(Element& e) {
  const auto& c = e.corners;
  const double abc = TriangleArea(c[0], c[1], c[2]);
  Vec3 weighted = (c[0] + c[1] + c[2]) * (abc / 3);
  double area = abc;
  if (!e.triangle) {
    const double acd = TriangleArea(c[0], c[2], c[3]);
    weighted += (c[0] + c[2] + c[3]) * (acd / 3);
    area += acd;
  }
  e.area = area;
  e.centroid = area > 0 ? weighted / area : c[0];
}

// Exact position key of a vertex within one face.
struct VertexKey {
  uint32_t face;
  uint64_t x, y, z;
  bool operator==(const VertexKey&) const = default;
};
struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    uint64_t h = k.face * 0x9e3779b97f4a7c15ull;
    for (uint64_t v : {k.x, k.y, k.z}) h = (h ^ v) * 0xff51afd7ed558ccdull;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};
VertexKey KeyOf(uint32_t face, const Vec3& p) {
  // +0.0 and -0.0 are the same point.
  auto bits = [](double v) { return std::bit_cast<uint64_t>(v == 0 ? 0.0 : v); };
  return {face, bits(p.x), bits(p.y), bits(p.z)};
}

class VertexIndex {
 public:
  explicit VertexIndex(PatchMesh& mesh) : mesh_(mesh) {}
  uint32_t Get(uint32_t face, const Vec3& p) {
    auto [it, inserted] = map_.try_emplace(KeyOf(face, p), 0);
    if (inserted) {
      it->second = static_cast<uint32_t>(mesh_.positions.size());
      mesh_.positions.push_back(p);
    }
    return it->second;
  }
  void Mark(uint32_t face, const Vec3& p) { corners_.try_emplace(KeyOf(face, p), 0); }
  bool IsCorner(uint32_t face, const Vec3& p) const { return corners_.count(KeyOf(face, p)) > 0; }

 private:
  PatchMesh& mesh_;
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> map_;
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> corners_;
};

// Leaf corners of the same face lying strictly inside edge (a, b), in order from a.
void HangingVertices(const VertexIndex& index, uint32_t face, const Vec3& a, const Vec3& b,
                     int depth, std::vector<Vec3>& out) {
  if (depth > 60) return;
  const Vec3 m = Mid(a, b);
  if (m == a || m == b || !index.IsCorner(face, m)) return;
  HangingVertices(index, face, a, m, depth + 1, out);
  out.push_back(m);
  HangingVertices(index, face, m, b, depth + 1, out);
}

void AddPatch(PatchMesh& mesh, const Element& e, std::array<uint32_t, 4> v) {
  Patch patch;
  patch.v = v;
  patch.face = e.face;
  patch.two_sided = e.two_sided;
  patch.opacity = e.opacity;
  const Vec3& normal = e.normal;
  FinishPatch(mesh.positions, normal, patch);
  mesh.patches.push_back(patch);
}

}  // namespace

ElementTree ElementTree::FromMesh(const PatchMesh& mesh) {
  ElementTree tree;
  tree.nodes.reserve(mesh.size());
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    Element e;
    for (int k = 0; k < 4; ++k) e.corners[k] = mesh.Vertex(p, k);
    e.triangle = patch.IsTriangle();
    e.face = patch.face;
    e.normal = patch.normal;
    e.two_sided = patch.two_sided;
    e.opacity = patch.opacity;
    FinishElement(e);
    tree.roots.push_back(static_cast<uint32_t>(tree.nodes.size()));
    tree.nodes.push_back(e);
  }
  return tree;
}

uint32_t ElementTree::Split(uint32_t node) {
  const Element parent = nodes[node];
  const auto& c = parent.corners;
  std::array<std::array<Vec3, 4>, 4> kids;
  if (parent.triangle) {
    const Vec3 ab = Mid(c[0], c[1]), bc = Mid(c[1], c[2]), ca = Mid(c[2], c[0]);
    kids = {{{c[0], ab, ca, ca}, {ab, c[1], bc, bc}, {ca, bc, c[2], c[2]}, {ab, bc, ca, ca}}};
  } else {
    const Vec3 ab = Mid(c[0], c[1]), bc = Mid(c[1], c[2]), cd = Mid(c[2], c[3]),
               da = Mid(c[3], c[0]);
    const Vec3 m = (c[0] + c[1] + c[2] + c[3]) * 0.25;
    kids = {{{c[0], ab, m, da}, {ab, c[1], bc, m}, {m, bc, c[2], cd}, {da, m, cd, c[3]}}};
  }
  const uint32_t first = static_cast<uint32_t>(nodes.size());
  for (const auto& corners : kids) {
    Element e;
    e.corners = corners;
    e.triangle = parent.triangle;
    e.two_sided = parent.two_sided;
    e.opacity = parent.opacity;
    e.face = parent.face;
    e.parent = node;
    e.depth = parent.depth + 1;
    e.normal = parent.normal;
    FinishElement(e);
    nodes.push_back(e);
  }
  nodes[node].first_child = first;
  return first;
}

std::vector<uint32_t> ElementTree::Leaves() const {
  std::vector<uint32_t> leaves, stack;
  for (uint32_t root : roots) {
    stack.push_back(root);
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      if (nodes[n].IsLeaf()) {
        leaves.push_back(n);
        continue;
      }
      for (int k = 3; k >= 0; --k) stack.push_back(nodes[n].first_child + k);
    }
  }
  return leaves;
}

Vec3 SampleElementPoint(const Element& e, Point2 u) {
  const auto& c = e.corners;
  auto tri = [](const Vec3& a, const Vec3& b, const Vec3& d, Point2 v) {
    const auto [b0, b1] = SampleUniformTriangle(v);
    return a * b0 + b * b1 + d * (1 - b0 - b1);
  };
  const double first = e.triangle ? 1.0 : TriangleArea(c[0], c[1], c[2]) / e.area;
  if (u.x < first) return tri(c[0], c[1], c[2], {u.x / first, u.y});
  return tri(c[0], c[2], c[3], {std::min((u.x - first) / (1 - first), 0x1.fffffffffffffp-1), u.y});
}

std::vector<Vec3> ElementPolygon(const Element& e) {
  return {e.corners.begin(), e.corners.begin() + e.CornerCount()};
}

PatchMesh BuildLeafMesh(const ElementTree& tree, const std::vector<uint32_t>& leaves,
                        bool conforming, std::vector<uint32_t>* patch_leaf) {
  PatchMesh mesh;
  VertexIndex index(mesh);
  if (conforming) {
    for (uint32_t n : leaves) {
      const Element& e = tree.nodes[n];
      for (int k = 0; k < e.CornerCount(); ++k) index.Mark(e.face, e.corners[k]);
    }
  }
  if (patch_leaf) patch_leaf->clear();
  std::vector<Vec3> boundary;
  for (uint32_t li = 0; li < leaves.size(); ++li) {
    const Element& e = tree.nodes[leaves[li]];
    while (mesh.face_first_patch.size() <= e.face) {
      mesh.face_first_patch.push_back(static_cast<uint32_t>(mesh.patches.size()));
      mesh.face_first_vertex.push_back(static_cast<uint32_t>(mesh.positions.size()));
    }
    boundary.clear();
    const int corners = e.CornerCount();
    for (int k = 0; k < corners; ++k) {
      boundary.push_back(e.corners[k]);
      if (conforming) {
        HangingVertices(index, e.face, e.corners[k], e.corners[(k + 1) % corners], 0, boundary);
      }
    }
    if (static_cast<int>(boundary.size()) == corners) {
      std::array<uint32_t, 4> v;
      for (int k = 0; k < 4; ++k) v[k] = index.Get(e.face, e.corners[k]);
      AddPatch(mesh, e, v);
    } else {
      const uint32_t centre = index.Get(e.face, e.centroid);
      for (size_t k = 0; k < boundary.size(); ++k) {
        const uint32_t a = index.Get(e.face, boundary[k]);
        const uint32_t b = index.Get(e.face, boundary[(k + 1) % boundary.size()]);
        AddPatch(mesh, e, {centre, a, b, b});
      }
    }
    if (patch_leaf) patch_leaf->resize(mesh.patches.size(), li);
  }
  // The closing sentinels.
  mesh.face_first_patch.push_back(static_cast<uint32_t>(mesh.patches.size()));
  mesh.face_first_vertex.push_back(static_cast<uint32_t>(mesh.positions.size()));
  return mesh;
}

}  // namespace radflux
