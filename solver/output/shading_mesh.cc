#include "solver/output/shading_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <utility>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

// A uniform grid of points: each cell holds a chain of point ids (head per cell, next per
// point), so inserting and visiting a cell's points allocate nothing per point.
class PointGrid {
 public:
  PointGrid(double cell, size_t points) : cell_(cell), next_(points, kEnd) {}

  void Insert(uint32_t id, const Vec3& p) {
    auto [it, inserted] = heads_.try_emplace(CellOf(p), id);
    if (!inserted) {
      next_[id] = it->second;
      it->second = id;
    }
  }

  // Calls visit(id) for every point in the 3x3x3 cells around p's cell.
  template <typename Visit>
  void ForNear(const Vec3& p, Visit&& visit) const {
    const Key c = CellOf(p);
    ForCells({c.x - 1, c.y - 1, c.z - 1}, {c.x + 1, c.y + 1, c.z + 1}, visit);
  }

  // Number of cells the box [lo, hi] overlaps.
  double CellsIn(const Vec3& lo, const Vec3& hi) const {
    const Key a = CellOf(lo), b = CellOf(hi);
    return double(b.x - a.x + 1) * double(b.y - a.y + 1) * double(b.z - a.z + 1);
  }

  // Calls visit(id) once for every point in the cells the box [lo, hi] overlaps.
  template <typename Visit>
  void ForBox(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    ForCells(CellOf(lo), CellOf(hi), visit);
  }

 private:
  static constexpr uint32_t kEnd = 0xffffffffu;
  struct Key {
    int64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  template <typename H>
  friend H AbslHashValue(H h, const Key& k) {
    return H::combine(std::move(h), k.x, k.y, k.z);
  }
  template <typename Visit>
  void ForCells(const Key& a, const Key& b, Visit& visit) const {
    for (int64_t x = a.x; x <= b.x; ++x) {
      for (int64_t y = a.y; y <= b.y; ++y) {
        for (int64_t z = a.z; z <= b.z; ++z) {
          const auto it = heads_.find({x, y, z});
          if (it == heads_.end()) continue;
          for (uint32_t id = it->second; id != kEnd; id = next_[id]) visit(id);
        }
      }
    }
  }
  Key CellOf(const Vec3& p) const {
    return {static_cast<int64_t>(std::floor(p.x / cell_)),
            static_cast<int64_t>(std::floor(p.y / cell_)),
            static_cast<int64_t>(std::floor(p.z / cell_))};
  }

  double cell_;
  std::vector<uint32_t> next_;
  absl::flat_hash_map<Key, uint32_t> heads_;
};

uint32_t Find(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// What decides whether two points may share a shading vertex: their face's material and
// normal (the face of the first patch that uses the point).
struct PointSurface {
  uint32_t material = 0xffffffffu;  // none: no patch uses the point, it is never welded
  Vec3 normal{0, 0, 1};
};

struct Context {
  const PatchMesh& mesh;
  double tolerance;  // scene units
  double cos_crease;
};

bool Compatible(const Context& c, const PointSurface& a, const PointSurface& b) {
  return a.material == b.material && a.material != 0xffffffffu &&
         Dot(a.normal, b.normal) >= c.cos_crease;
}

std::vector<PointSurface> PointSurfaces(const PatchMesh& mesh,
                                        const std::vector<uint32_t>& face_material) {
  std::vector<PointSurface> surfaces(mesh.positions.size());
  for (const Patch& patch : mesh.patches) {
    for (int k = 0; k < patch.VertexCount(); ++k) {
      PointSurface& s = surfaces[patch.v[k]];
      if (s.material == 0xffffffffu) s = {face_material[patch.face], patch.normal};
    }
  }
  return surfaces;
}

// Welded id per position: union of compatible positions within the tolerance, numbered in
// the order of their first position.
void Weld(const Context& c, const std::vector<PointSurface>& surfaces, ShadingMesh& out) {
  const size_t n = c.mesh.positions.size();
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  PointGrid grid(c.tolerance * 2, n);
  const double tol2 = c.tolerance * c.tolerance;
  const Vec3 reach{c.tolerance, c.tolerance, c.tolerance};
  for (uint32_t i = 0; i < n; ++i) {
    const Vec3& p = c.mesh.positions[i];
    // Only the cells the tolerance box around p overlaps (at most 2 a side, not 3x3x3).
    grid.ForBox(p - reach, p + reach, [&](uint32_t j) {
      const Vec3 d = c.mesh.positions[j] - p;
      if (Dot(d, d) <= tol2 && Compatible(c, surfaces[i], surfaces[j])) {
        parent[Find(parent, i)] = Find(parent, j);
      }
    });
    grid.Insert(i, p);
  }
  out.welded.assign(n, 0);
  std::vector<uint32_t> id_of_root(n, 0xffffffffu);
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t& id = id_of_root[Find(parent, i)];
    if (id == 0xffffffffu) {
      id = static_cast<uint32_t>(out.representative.size());
      out.representative.push_back(i);
    }
    out.welded[i] = id;
  }
}

// Incident patches (CSR) and area-weighted normals per welded vertex.
void Incidence(const PatchMesh& mesh, ShadingMesh& out) {
  const size_t w = out.size();
  out.first_patch.assign(w + 1, 0);
  std::vector<Vec3> sum(w);
  auto for_corners = [&](auto&& body) {
    for (uint32_t p = 0; p < mesh.size(); ++p) {
      const Patch& patch = mesh.patches[p];
      for (int k = 0; k < patch.VertexCount(); ++k) body(p, out.welded[patch.v[k]]);
    }
  };
  for_corners([&](uint32_t, uint32_t v) { ++out.first_patch[v + 1]; });
  std::partial_sum(out.first_patch.begin(), out.first_patch.end(), out.first_patch.begin());
  out.vertex_patches.resize(out.first_patch.back());
  std::vector<uint32_t> fill(out.first_patch.begin(), out.first_patch.end() - 1);
  for_corners([&](uint32_t p, uint32_t v) {
    out.vertex_patches[fill[v]++] = p;
    sum[v] += mesh.patches[p].normal * mesh.patches[p].area;
  });
  out.normals.resize(w);
  for (size_t v = 0; v < w; ++v) {
    out.normals[v] = Length(sum[v]) > 0 ? Normalize(sum[v]) : Vec3{0, 0, 1};
  }
}

struct Edge {
  uint32_t patch;
  int edge;
};

// Patch edges used by one patch only (after welding): where T-junctions can be. Every edge's
// welded key, sorted: a key that occurs once is a boundary edge (in patch order).
std::vector<Edge> BoundaryEdges(const PatchMesh& mesh, const ShadingMesh& s) {
  std::vector<Edge> all;
  std::vector<std::pair<uint64_t, uint32_t>> keys;  // (welded key, index into all)
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    for (int k = 0; k < patch.VertexCount(); ++k) {
      const uint64_t a = s.welded[patch.v[k]];
      const uint64_t b = s.welded[patch.v[(k + 1) % patch.VertexCount()]];
      keys.push_back({std::min(a, b) << 32 | std::max(a, b), static_cast<uint32_t>(all.size())});
      all.push_back({p, k});
    }
  }
  std::sort(keys.begin(), keys.end());
  std::vector<bool> boundary(all.size(), false);
  for (size_t i = 0, j = 0; i < keys.size(); i = j) {
    for (j = i + 1; j < keys.size() && keys[j].first == keys[i].first;) ++j;
    if (j == i + 1) boundary[keys[i].second] = true;
  }
  std::vector<Edge> edges;
  for (size_t e = 0; e < all.size(); ++e) {
    if (boundary[e]) edges.push_back(all[e]);
  }
  return edges;
}

// The welded vertices of `candidates` (near edge e) that lie strictly inside it, on the
// same smooth surface as its patch.
void EdgeJunctions(const Context& c, const ShadingMesh& s,
                   const std::vector<PointSurface>& surfaces, const Edge& e,
                   const std::vector<uint32_t>& candidates, std::vector<TJunction>& out) {
  const Patch& patch = c.mesh.patches[e.patch];
  const uint32_t a = s.welded[patch.v[e.edge]];
  const uint32_t b = s.welded[patch.v[(e.edge + 1) % patch.VertexCount()]];
  const Vec3 pa = c.mesh.positions[patch.v[e.edge]];
  const Vec3 ab = c.mesh.positions[patch.v[(e.edge + 1) % patch.VertexCount()]] - pa;
  const double length2 = Dot(ab, ab);
  if (!(length2 > 0)) return;
  const PointSurface own = surfaces[patch.v[e.edge]];
  for (uint32_t v : candidates) {
    if (v == a || v == b) continue;
    const uint32_t rep = s.representative[v];
    if (!Compatible(c, own, surfaces[rep])) continue;
    const Vec3 d = c.mesh.positions[rep] - pa;
    const double t = Dot(d, ab) / length2;
    const double margin = c.tolerance / std::sqrt(length2);
    if (t <= margin || t >= 1 - margin) continue;
    const Vec3 off = d - ab * t;
    if (Dot(off, off) <= c.tolerance * c.tolerance) out.push_back({v, e.patch, e.edge, t});
  }
}

void FindTJunctions(const Context& c, const std::vector<PointSurface>& surfaces, ShadingMesh& s) {
  const std::vector<Edge> edges = BoundaryEdges(c.mesh, s);
  if (edges.empty()) return;
  std::vector<bool> on_boundary(s.size(), false);
  std::vector<double> lengths;
  lengths.reserve(edges.size());
  for (const Edge& e : edges) {
    const Patch& patch = c.mesh.patches[e.patch];
    const uint32_t i = patch.v[e.edge], j = patch.v[(e.edge + 1) % patch.VertexCount()];
    on_boundary[s.welded[i]] = on_boundary[s.welded[j]] = true;
    lengths.push_back(Length(c.mesh.positions[j] - c.mesh.positions[i]));
  }
  // Cells of the median edge's size: a few long edges neither crowd fine detail into one
  // cell nor cost more than a walk of their length.
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  const double cell = std::max(lengths[lengths.size() / 2], c.tolerance * 4);
  PointGrid grid(cell, s.size());
  for (uint32_t v = 0; v < s.size(); ++v) {
    if (on_boundary[v]) grid.Insert(v, c.mesh.positions[s.representative[v]]);
  }
  std::vector<uint32_t> candidates;
  const Vec3 margin{c.tolerance, c.tolerance, c.tolerance};
  for (const Edge& e : edges) {
    const Patch& patch = c.mesh.patches[e.patch];
    const Vec3 a = c.mesh.positions[patch.v[e.edge]];
    const Vec3 b = c.mesh.positions[patch.v[(e.edge + 1) % patch.VertexCount()]];
    const Vec3 lo = Vec3{std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)} - margin;
    const Vec3 hi = Vec3{std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)} + margin;
    candidates.clear();
    auto take = [&](uint32_t v) { candidates.push_back(v); };
    if (grid.CellsIn(lo, hi) <= 64) {  // the usual edge: the cells of its box, once each
      grid.ForBox(lo, hi, take);
    } else {  // a long slanted edge: the cells around points a cell apart along it
      const int steps = static_cast<int>(std::ceil(Length(b - a) / cell));
      for (int i = 0; i <= steps; ++i) grid.ForNear(a + (b - a) * (double(i) / steps), take);
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    }
    EdgeJunctions(c, s, surfaces, e, candidates, s.t_junctions);
  }
  std::sort(s.t_junctions.begin(), s.t_junctions.end(), [](const TJunction& x, const TJunction& y) {
    return std::tie(x.patch, x.edge, x.t) < std::tie(y.patch, y.edge, y.t);
  });
}

}  // namespace

std::vector<uint32_t> FaceMaterials(const Scene& scene) {
  std::vector<uint32_t> materials;
  materials.reserve(scene.faces.size());
  for (const Face& face : scene.faces) materials.push_back(face.material);
  return materials;
}

absl::StatusOr<ShadingMesh> BuildShadingMesh(const PatchMesh& mesh,
                                             const std::vector<uint32_t>& face_material,
                                             const ShadingOptions& options) {
  if (!(options.crease_degrees >= 0 && options.crease_degrees <= 180) ||
      !(options.weld_tolerance > 0 && options.weld_tolerance < 1)) {
    return absl::InvalidArgumentError("shading: crease angle or weld tolerance out of range");
  }
  for (const Patch& patch : mesh.patches) {
    if (patch.face >= face_material.size()) {
      return absl::InvalidArgumentError(absl::StrCat("shading: patch of face ", patch.face, " but ",
                                                     face_material.size(), " face materials"));
    }
    for (int k = 0; k < patch.VertexCount(); ++k) {
      if (patch.v[k] >= mesh.positions.size()) {
        return absl::InvalidArgumentError(absl::StrCat("shading: a patch uses vertex ", patch.v[k],
                                                       " of ", mesh.positions.size()));
      }
    }
  }
  Vec3 lo = mesh.positions.empty() ? Vec3{} : mesh.positions[0], hi = lo;
  for (const Vec3& p : mesh.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double diagonal = Length(hi - lo);
  const Context c{mesh, diagonal > 0 ? options.weld_tolerance * diagonal : 1.0,
                  std::cos(options.crease_degrees * std::numbers::pi / 180)};
  const std::vector<PointSurface> surfaces = PointSurfaces(mesh, face_material);
  ShadingMesh shading;
  Weld(c, surfaces, shading);
  Incidence(mesh, shading);
  FindTJunctions(c, surfaces, shading);
  return shading;
}

std::vector<uint32_t> PatchOutline(const PatchMesh& mesh, const ShadingMesh& shading, uint32_t p) {
  const Patch& patch = mesh.patches[p];
  auto it = std::lower_bound(shading.t_junctions.begin(), shading.t_junctions.end(), p,
                             [](const TJunction& j, uint32_t q) { return j.patch < q; });
  std::vector<uint32_t> outline;
  for (int k = 0; k < patch.VertexCount(); ++k) {
    outline.push_back(shading.welded[patch.v[k]]);
    for (; it != shading.t_junctions.end() && it->patch == p && it->edge == k; ++it) {
      outline.push_back(it->vertex);
    }
  }
  return outline;
}

}  // namespace radflux
