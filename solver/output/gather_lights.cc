#include "solver/output/gather_lights.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace radflux {
namespace {

struct Planar {
  double s = 0, t = 0;
  uint32_t vertex = 0;
};

double Turn(const Planar& o, const Planar& a, const Planar& b) {
  return (a.s - o.s) * (b.t - o.t) - (a.t - o.t) * (b.s - o.s);
}

// The corners of the convex hull of `points`, counter-clockwise, collinear points dropped
// (Andrew's monotone chain); `tolerance` is the smallest turn (twice a triangle's area) kept.
std::vector<Planar> ConvexHull(std::vector<Planar> points, double tolerance) {
  std::sort(points.begin(), points.end(), [](const Planar& a, const Planar& b) {
    return std::make_pair(a.s, a.t) < std::make_pair(b.s, b.t);
  });
  std::vector<Planar> hull(2 * points.size());
  size_t k = 0;
  for (size_t pass = 0; pass < 2; ++pass) {
    const size_t floor = k;
    for (const Planar& p : points) {
      while (k >= floor + 2 && Turn(hull[k - 2], hull[k - 1], p) <= tolerance) --k;
      hull[k++] = p;
    }
    --k;  // the last point starts the other chain
    std::reverse(points.begin(), points.end());
  }
  hull.resize(k);
  return hull;
}

double HullArea(const std::vector<Planar>& hull) {
  double twice = 0;
  for (size_t k = 0; k < hull.size(); ++k) {
    const Planar& a = hull[k];
    const Planar& b = hull[(k + 1) % hull.size()];
    twice += a.s * b.t - b.s * a.t;
  }
  return twice / 2;
}

// The face of `patches` as one convex triangle or quad (vertex indices of `mesh`, ccw about
// the normal), or nothing when the patches do not tile one.
std::vector<uint32_t> ConvexOutline(const PatchMesh& mesh, const std::vector<uint32_t>& patches) {
  const Frame frame = Frame::FromNormal(mesh.patches[patches[0]].normal);
  std::vector<Planar> points;
  double area = 0, extent = 0;
  for (uint32_t p : patches) {
    area += mesh.patches[p].area;
    for (int k = 0; k < mesh.patches[p].VertexCount(); ++k) {
      const uint32_t v = mesh.patches[p].v[k];
      const Vec3 local = frame.ToLocal(mesh.positions[v]);
      points.push_back({local.x, local.y, v});
      extent = std::max({extent, std::abs(local.x), std::abs(local.y)});
    }
  }
  const std::vector<Planar> hull = ConvexHull(points, 1e-9 * area);
  if (hull.size() < 3 || hull.size() > 4 || std::abs(HullArea(hull) - area) > 1e-6 * area)
    return {};
  std::vector<uint32_t> outline;
  for (const Planar& corner : hull) outline.push_back(corner.vertex);
  return outline;
}

// Appends one light patch with corners `outline` (vertex indices of `source`), as opaque
// as patch `first` of `source`.
void AddLight(const PatchMesh& source, uint32_t first, const std::vector<uint32_t>& outline,
              const Vec3& normal, GatherLights& lights) {
  Patch patch;
  for (size_t k = 0; k < 4; ++k) {
    patch.v[k] = static_cast<uint32_t>(lights.mesh.positions.size() +
                                       std::min<size_t>(k, outline.size() - 1));
  }
  for (uint32_t v : outline) lights.mesh.positions.push_back(source.positions[v]);
  patch.face = static_cast<uint32_t>(lights.mesh.patches.size());
  patch.opacity = source.patches[first].opacity;
  FinishPatch(lights.mesh.positions, normal, patch);
  lights.mesh.patches.push_back(patch);
}

}  // namespace

GatherLights MakeGatherLights(const PatchMesh& mesh, const PatchAttributes& attributes) {
  std::map<uint32_t, std::vector<uint32_t>> emitting_faces;  // face -> its emitting patches
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    if (MaxComponent(attributes.emission[p]) > 0) emitting_faces[mesh.patches[p].face].push_back(p);
  }
  GatherLights lights;
  lights.of_patch.assign(mesh.size(), kNoLight);
  for (const auto& [face, patches] : emitting_faces) {
    const Vec3 normal = mesh.patches[patches[0]].normal;
    std::vector<uint32_t> outline = ConvexOutline(mesh, patches);
    const auto& first_emission = attributes.emission[patches[0]];  // (clang 14 cannot
    // capture a structured binding)
    const bool merged =
        !outline.empty() && std::all_of(patches.begin(), patches.end(), [&](uint32_t p) {
          return attributes.emission[p] == first_emission;
        });
    for (uint32_t p : patches) {
      if (!merged || p == patches[0]) {
        if (!merged) {
          const Patch& patch = mesh.patches[p];
          outline.assign(patch.v.begin(), patch.v.begin() + patch.VertexCount());
        }
        AddLight(mesh, p, outline, normal, lights);
        lights.emission.push_back(attributes.emission[p]);
      }
      lights.of_patch[p] = static_cast<uint32_t>(lights.mesh.size() - 1);
    }
  }
  return lights;
}

}  // namespace radflux
