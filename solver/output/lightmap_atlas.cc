#include "solver/output/lightmap_atlas.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

// A face's extent in its plane, scene units.
struct FaceExtent {
  uint32_t face = 0;
  Frame frame;
  double s0 = 0, t0 = 0, s1 = 0, t1 = 0;
};

std::vector<FaceExtent> FaceExtents(const PatchMesh& mesh) {
  std::map<uint32_t, FaceExtent> by_face;
  for (const Patch& patch : mesh.patches) {
    auto [it, added] = by_face.try_emplace(patch.face);
    FaceExtent& e = it->second;
    if (added) {
      e.face = patch.face;
      e.frame = Frame::FromNormal(patch.normal);
      e.s0 = e.t0 = std::numeric_limits<double>::infinity();
      e.s1 = e.t1 = -std::numeric_limits<double>::infinity();
    }
    for (int k = 0; k < patch.VertexCount(); ++k) {
      const Vec3 local = e.frame.ToLocal(mesh.positions[patch.v[k]]);
      e.s0 = std::min(e.s0, local.x), e.s1 = std::max(e.s1, local.x);
      e.t0 = std::min(e.t0, local.y), e.t1 = std::max(e.t1, local.y);
    }
  }
  std::vector<FaceExtent> extents;
  for (const auto& [face, e] : by_face) extents.push_back(e);
  return extents;
}

// Packs rectangles of the extents at `density` texels per unit on shelves, tallest first;
// false when they do not fit in size x size.
bool Pack(const std::vector<FaceExtent>& extents, double density, int size, int gutter,
          std::vector<LightmapChart>& charts) {
  charts.assign(extents.size(), {});
  for (size_t k = 0; k < extents.size(); ++k) {
    const FaceExtent& e = extents[k];
    LightmapChart& c = charts[k];
    c.face = e.face, c.frame = e.frame, c.s0 = e.s0, c.t0 = e.t0;
    c.width = static_cast<int>(std::ceil((e.s1 - e.s0) * density)) + 2 * gutter;
    c.height = static_cast<int>(std::ceil((e.t1 - e.t0) * density)) + 2 * gutter;
  }
  std::vector<size_t> order(charts.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return charts[a].height > charts[b].height; });
  int x = 0, y = 0, shelf = 0;
  for (size_t k : order) {
    LightmapChart& c = charts[k];
    if (c.width > size) return false;
    if (x + c.width > size) x = 0, y += shelf, shelf = 0;
    if (y + c.height > size) return false;
    c.x = x, c.y = y;
    x += c.width;
    shelf = std::max(shelf, c.height);
  }
  return true;
}

}  // namespace

Point2 LightmapAtlas::Texel(const LightmapChart& chart, const Vec3& p) const {
  const Vec3 local = chart.frame.ToLocal(p);
  return {chart.x + gutter + (local.x - chart.s0) * texels_per_unit,
          chart.y + gutter + (local.y - chart.t0) * texels_per_unit};
}

Point2 LightmapAtlas::Uv(const LightmapChart& chart, const Vec3& p) const {
  const Point2 texel = Texel(chart, p);
  return {texel.x / size, texel.y / size};
}

absl::StatusOr<LightmapAtlas> BuildLightmapAtlas(const PatchMesh& mesh, int size, int gutter) {
  if (size < 16 || size > 16384 || gutter < 2 || mesh.size() == 0) {
    return absl::InvalidArgumentError(absl::StrCat("lightmap: size ", size,
                                                   " must be in [16, 16384], gutter ", gutter,
                                                   " >= 2, mesh not empty"));
  }
  const std::vector<FaceExtent> extents = FaceExtents(mesh);
  double area = 0, longest = 0;
  for (const FaceExtent& e : extents) {
    area += (e.s1 - e.s0) * (e.t1 - e.t0);
    longest = std::max({longest, e.s1 - e.s0, e.t1 - e.t0});
  }
  LightmapAtlas atlas;
  atlas.size = size;
  atlas.gutter = gutter;
  // Start where the faces' boxes alone would fill the square, and shrink by 1% until they fit.
  double density = std::min(size / std::sqrt(area), (size - 2.0 * gutter) / longest);
  while (!Pack(extents, density, size, gutter, atlas.charts)) {
    density *= 0.99;
    if (density * longest < 1) {
      return absl::InvalidArgumentError(absl::StrCat("lightmap: ", extents.size(),
                                                     " faces do not fit in ", size, "x", size,
                                                     " texels with a ", gutter, "-texel gutter"));
    }
  }
  atlas.texels_per_unit = density;
  uint32_t faces = 0;
  for (const LightmapChart& c : atlas.charts) faces = std::max(faces, c.face + 1);
  atlas.chart_of_face.assign(faces, 0);
  for (uint32_t k = 0; k < atlas.charts.size(); ++k) atlas.chart_of_face[atlas.charts[k].face] = k;
  return atlas;
}

}  // namespace radflux
