#include "solver/formfactor/shaft_cull.h"

#include <algorithm>
#include <limits>

#include "solver/core/parallel.h"

namespace radflux {
namespace {

constexpr double kRelativeTolerance = 1e-9;

bool AnyVertexInFront(const SurfaceShape& plane, const std::vector<Vec3>& points, double tolerance) {
  for (const Vec3& p : points) {
    if (Dot(p - plane.centroid, plane.normal) > tolerance) return true;
  }
  return false;
}

// Whether the projections of the two point sets on `axis` are disjoint (with a margin).
bool Separates(const Vec3& axis, const SurfaceShape& i, const SurfaceShape& j,
               const SurfaceShape& k, double margin) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const SurfaceShape* s : {&i, &j}) {
    for (const Vec3& p : s->polygon) {
      const double d = Dot(p, axis);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  double klo = std::numeric_limits<double>::infinity(), khi = -klo;
  for (const Vec3& p : k.polygon) {
    const double d = Dot(p, axis);
    klo = std::min(klo, d);
    khi = std::max(khi, d);
  }
  const double scale = margin * Length(axis);
  return khi < lo - scale || klo > hi + scale;
}

}  // namespace

std::vector<uint32_t> PotentialBlockers(const std::vector<SurfaceShape>& shapes) {
  double extent = 0;
  for (const SurfaceShape& s : shapes) extent = std::max(extent, s.diameter);
  const double tolerance = kRelativeTolerance * extent;
  std::vector<uint8_t> blocks(shapes.size(), 0);
  ParallelFor(static_cast<int64_t>(shapes.size()), 256, 0, [&](int64_t begin, int64_t end) {
    for (int64_t k = begin; k < end; ++k) {
      const SurfaceShape& s = shapes[k];
      for (const SurfaceShape& other : shapes) {
        bool behind = false;
        for (const Vec3& p : other.polygon) behind = behind || Dot(p - s.centroid, s.normal) < -tolerance;
        if (behind) {
          blocks[k] = 1;
          break;
        }
      }
    }
  });
  std::vector<uint32_t> out;
  for (uint32_t k = 0; k < shapes.size(); ++k) {
    if (blocks[k]) out.push_back(k);
  }
  return out;
}

std::vector<uint32_t> RowBlockers(const std::vector<SurfaceShape>& shapes,
                                  const std::vector<uint32_t>& blockers, uint32_t i) {
  std::vector<uint32_t> out;
  const double tolerance = kRelativeTolerance * shapes[i].diameter;
  for (uint32_t k : blockers) {
    if (k != i && AnyVertexInFront(shapes[i], shapes[k].polygon, tolerance)) out.push_back(k);
  }
  return out;
}

bool ShaftMayHold(const SurfaceShape& i, const SurfaceShape& j, const SurfaceShape& k) {
  if (&k == &i || &k == &j) return false;
  const double size = i.diameter + j.diameter + k.diameter;
  const double margin = kRelativeTolerance * size;
  for (int c = 0; c < 3; ++c) {  // the coordinate axes: bounding boxes
    if (k.hi[c] < std::min(i.lo[c], j.lo[c]) - margin ||
        k.lo[c] > std::max(i.hi[c], j.hi[c]) + margin) {
      return false;
    }
  }
  if (!AnyVertexInFront(j, k.polygon, margin)) return false;
  const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const Vec3& n : {i.normal, j.normal, k.normal}) {
    if (Separates(n, i, j, k, margin)) return false;
  }
  const Vec3 d = j.centroid - i.centroid;
  for (size_t e = 0; e < k.polygon.size(); ++e) {
    const Vec3 axis = Cross(d, k.polygon[(e + 1) % k.polygon.size()] - k.polygon[e]);
    if (Dot(axis, axis) > 0 && Separates(axis, i, j, k, margin)) return false;
  }
  for (const Vec3& a : axes) {
    const Vec3 axis = Cross(d, a);
    if (Dot(axis, axis) > 0 && Separates(axis, i, j, k, margin)) return false;
  }
  return true;
}

}  // namespace radflux
