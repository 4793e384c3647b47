#include "solver/scene/face_shape.h"

#include <algorithm>
#include <cmath>

#include "solver/scene/scene.h"
#include "solver/scene/validation.h"

namespace radflux {
namespace {

bool IsConvex(const std::vector<Vec3>& polygon, const Vec3& n, double tolerance) {
  const size_t k = polygon.size();
  for (size_t i = 0; i < k; ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % k];
    const Vec3& c = polygon[(i + 2) % k];
    if (Dot(Cross(b - a, c - b), n) < -tolerance) return false;
  }
  return true;
}

}  // namespace

FaceShape MeasureFace(const std::vector<Vec3>& polygon) {
  FaceShape shape;
  const size_t k = polygon.size();
  for (size_t i = 0; i < k; ++i) {
    shape.finite = shape.finite && IsFinite(polygon[i]);
    shape.longest_edge = std::max(shape.longest_edge, Length(polygon[(i + 1) % k] - polygon[i]));
  }
  if (!shape.finite) return shape;
  const Vec3 newell = PolygonNewellNormal(polygon);
  shape.area = Length(newell) / 2;
  const double scale = shape.longest_edge * shape.longest_edge;
  shape.degenerate = !(shape.area > kDegenerateAreaTolerance * scale);
  if (shape.degenerate) return shape;
  shape.normal = newell / (2 * shape.area);
  Vec3 centroid;
  for (const Vec3& p : polygon) centroid += p / static_cast<double>(k);
  for (const Vec3& p : polygon) {
    shape.planarity_error = std::max(shape.planarity_error, std::abs(Dot(p - centroid, shape.normal)));
  }
  shape.planar = shape.planarity_error <= kPlanarityTolerance * shape.longest_edge;
  shape.convex = k == 3 || !shape.planar || IsConvex(polygon, shape.normal, kDegenerateAreaTolerance * scale);
  return shape;
}

}  // namespace radflux
