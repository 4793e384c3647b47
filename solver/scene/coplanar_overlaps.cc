#include "solver/scene/coplanar_overlaps.h"

#include <algorithm>
#include <cmath>
#include <tuple>


namespace radflux {
namespace {

struct Point2D {
  double x = 0, y = 0;
};
using Polygon2D = std::vector<Point2D>;

struct PlaneKey {
  int64_t nx, ny, nz, d;
  uint32_t face;
  auto Tie() const { return std::tie(nx, ny, nz, d); }
};

double SignedArea(const Polygon2D& p) {
  double twice = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Point2D& a = p[i];
    const Point2D& b = p[(i + 1) % p.size()];
    twice += a.x * b.y - a.y * b.x;
  }
  return twice / 2;
}

// Area of the intersection of two counter-clockwise convex polygons (Sutherland-Hodgman).
double IntersectionArea(Polygon2D subject, const Polygon2D& clip) {
  for (size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
    const Point2D& a = clip[i];
    const Point2D& b = clip[(i + 1) % clip.size()];
    auto side = [&](const Point2D& p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
    Polygon2D out;
    for (size_t k = 0; k < subject.size(); ++k) {
      const Point2D& p = subject[k];
      const Point2D& q = subject[(k + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) {
        const double t = sp / (sp - sq);
        out.push_back({p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t});
      }
    }
    subject = std::move(out);
  }
  return subject.size() < 3 ? 0 : SignedArea(subject);
}

// The faces of one plane, in 2D coordinates of the plane, each counter-clockwise.
struct PlaneFaces {
  std::vector<uint32_t> faces;
  std::vector<Polygon2D> polygons;
  std::vector<std::array<double, 4>> boxes;  // min x, min y, max x, max y
};

PlaneFaces Flatten(const Scene& scene, const std::vector<uint32_t>& faces, const Vec3& normal) {
  const Frame frame = Frame::FromNormal(normal);
  PlaneFaces plane;
  plane.faces = faces;
  for (uint32_t f : faces) {
    Polygon2D polygon;
    std::array<double, 4> box{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v : scene.faces[f].vertices) {
      const Point2D p{Dot(scene.positions[v], frame.s), Dot(scene.positions[v], frame.t)};
      polygon.push_back(p);
      box = {std::min(box[0], p.x), std::min(box[1], p.y), std::max(box[2], p.x), std::max(box[3], p.y)};
    }
    if (SignedArea(polygon) < 0) std::reverse(polygon.begin(), polygon.end());
    plane.polygons.push_back(std::move(polygon));
    plane.boxes.push_back(box);
  }
  return plane;
}

bool Twins(const Face& a, const Face& b) {
  if (a.vertices.size() != b.vertices.size()) return false;
  std::vector<uint32_t> va = a.vertices, vb = b.vertices;
  std::sort(va.begin(), va.end());
  std::sort(vb.begin(), vb.end());
  return va == vb;
}

// Overlapping pairs among one plane's faces, through a uniform grid over their boxes.
void OverlapsInPlane(const Scene& scene, const PlaneFaces& plane, std::vector<FaceOverlap>& out) {
  const size_t n = plane.faces.size();
  std::array<double, 4> all{INFINITY, INFINITY, -INFINITY, -INFINITY};
  std::vector<double> sizes;
  for (const auto& b : plane.boxes) {
    all = {std::min(all[0], b[0]), std::min(all[1], b[1]), std::max(all[2], b[2]), std::max(all[3], b[3])};
    sizes.push_back(std::max(b[2] - b[0], b[3] - b[1]));
  }
  std::nth_element(sizes.begin(), sizes.begin() + n / 2, sizes.end());
  double cell = std::max({sizes[n / 2], (all[2] - all[0]) / 256, (all[3] - all[1]) / 256, 1e-300});
  auto cell_of = [&](double v, double lo) { return static_cast<int64_t>(std::floor((v - lo) / cell)); };
  auto cells_of = [&](size_t i) {
    const auto& b = plane.boxes[i];
    return (cell_of(b[2], all[0]) - cell_of(b[0], all[0]) + 1) * (cell_of(b[3], all[1]) - cell_of(b[1], all[1]) + 1);
  };
  for (;;) {  // coarsen until the grid holds at most 16 entries per face
    int64_t total = 0;
    for (size_t i = 0; i < n; ++i) total += cells_of(i);
    if (total <= 16 * static_cast<int64_t>(n)) break;
    cell *= 2;
  }
  const int64_t columns = cell_of(all[2], all[0]) + 1;
  std::vector<std::pair<int64_t, uint32_t>> entries;  // (cell, index in plane)
  for (uint32_t i = 0; i < n; ++i) {
    const auto& b = plane.boxes[i];
    for (int64_t y = cell_of(b[1], all[1]); y <= cell_of(b[3], all[1]); ++y) {
      for (int64_t x = cell_of(b[0], all[0]); x <= cell_of(b[2], all[0]); ++x) entries.push_back({y * columns + x, i});
    }
  }
  std::sort(entries.begin(), entries.end());
  for (size_t s = 0; s < entries.size();) {
    size_t e = s;
    while (e < entries.size() && entries[e].first == entries[s].first) ++e;
    for (size_t p = s; p < e; ++p) {
      for (size_t q = p + 1; q < e; ++q) {
        const uint32_t i = entries[p].second, j = entries[q].second;
        const auto &bi = plane.boxes[i], &bj = plane.boxes[j];
        const double lo_x = std::max(bi[0], bj[0]), lo_y = std::max(bi[1], bj[1]);
        if (lo_x >= std::min(bi[2], bj[2]) || lo_y >= std::min(bi[3], bj[3])) continue;
        // Each pair is tested once: in the cell holding the low corner of the boxes' overlap.
        if (cell_of(lo_y, all[1]) * columns + cell_of(lo_x, all[0]) != entries[s].first) continue;
        const Face &fi = scene.faces[plane.faces[i]], &fj = scene.faces[plane.faces[j]];
        if (Twins(fi, fj)) continue;
        const double smaller = std::min(SignedArea(plane.polygons[i]), SignedArea(plane.polygons[j]));
        if (IntersectionArea(plane.polygons[i], plane.polygons[j]) > 1e-3 * smaller) {
          out.push_back({std::min(plane.faces[i], plane.faces[j]), std::max(plane.faces[i], plane.faces[j])});
        }
      }
    }
    s = e;
  }
}

}  // namespace

std::vector<FaceOverlap> FindCoplanarOverlaps(const Scene& scene) {
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const Vec3& p : scene.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double step = std::max(1e-5 * Length(hi - lo), 1e-300);
  std::vector<PlaneKey> keys;
  keys.reserve(scene.faces.size());
  std::vector<Vec3> polygon;
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    FacePolygonInto(scene, scene.faces[f], polygon);
    Vec3 n = Normalize(PolygonNewellNormal(polygon));
    const double major = std::abs(n.x) >= std::max(std::abs(n.y), std::abs(n.z)) ? n.x
                         : std::abs(n.y) >= std::abs(n.z)                        ? n.y
                                                                                 : n.z;
    if (major < 0) n = -n;  // both facings of a plane share a key
    keys.push_back({std::llround(n.x * 1e4), std::llround(n.y * 1e4), std::llround(n.z * 1e4),
                    std::llround(Dot(n, polygon[0]) / step), f});
  }
  std::sort(keys.begin(), keys.end(), [](const PlaneKey& a, const PlaneKey& b) {
    return std::tie(a.nx, a.ny, a.nz, a.d, a.face) < std::tie(b.nx, b.ny, b.nz, b.d, b.face);
  });
  std::vector<FaceOverlap> overlaps;
  for (size_t s = 0; s < keys.size();) {
    size_t e = s;
    std::vector<uint32_t> faces;
    while (e < keys.size() && keys[e].Tie() == keys[s].Tie()) faces.push_back(keys[e++].face);
    if (faces.size() > 1) {
      const Vec3 normal = Normalize(Vec3(keys[s].nx, keys[s].ny, keys[s].nz));
      OverlapsInPlane(scene, Flatten(scene, faces, normal), overlaps);
    }
    s = e;
  }
  std::sort(overlaps.begin(), overlaps.end(),
            [](const FaceOverlap& x, const FaceOverlap& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  return overlaps;
}

}  // namespace radflux
