#include "solver/formfactor/emitter_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include "solver/core/spherical_sampling.h"
#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

// A quad whose opposite sides are equal and whose adjacent sides are orthogonal, to a
// relative 1e-9 of its size: Urena et al.'s map applies.
bool IsRectangle(const std::array<Vec3, 4>& c) {
  const Vec3 ex = c[1] - c[0], ey = c[3] - c[0];
  const double size2 = Dot(ex, ex) + Dot(ey, ey);
  const Vec3 gap = c[2] - (c[1] + ey);
  return Dot(gap, gap) <= 1e-18 * size2 && std::abs(Dot(ex, ey)) <= 1e-9 * size2;
}

}  // namespace

EmitterShape MakeEmitterShape(const PatchMesh& mesh, uint32_t p, double exitance) {
  const Patch& patch = mesh.patches[p];
  EmitterShape shape;
  shape.patch = p;
  shape.corners = static_cast<uint32_t>(patch.VertexCount());
  for (int k = 0; k < 4; ++k) shape.corner[k] = mesh.Vertex(p, k);
  shape.normal = patch.normal;
  shape.area = patch.area;
  shape.opacity = patch.opacity;
  shape.power = exitance * patch.area * patch.opacity;
  shape.rectangle = shape.corners == 4 && IsRectangle(shape.corner);
  return shape;
}

double EmitterFormFactor(const EmitterShape& shape, const Vec3& x, const Vec3& n) {
  if (!(Dot(x - shape.corner[0], shape.normal) > 0)) return 0;  // x sees the back side
  const std::span<const Vec3> polygon(shape.corner.data(), shape.corners);
  return PointToPolygonFormFactor(x, n, polygon);
}

bool EmitterHit(const EmitterShape& shape, const Vec3& x, const Vec3& w, Vec3& point) {
  const double along = Dot(w, shape.normal);
  if (!(along < 0)) return false;
  const double t = Dot(shape.corner[0] - x, shape.normal) / along;
  if (!(t > 0)) return false;
  point = x + w * t;
  // Inside a convex ccw polygon: left of every edge, seen from the front.
  for (uint32_t k = 0; k < shape.corners; ++k) {
    const Vec3& a = shape.corner[k];
    const Vec3& b = shape.corner[(k + 1) % shape.corners];
    if (Dot(Cross(b - a, point - a), shape.normal) < 0) return false;
  }
  return true;
}

double EmitterImportance(const EmitterShape& shape, double form_factor) {
  return shape.power / shape.area * std::numbers::pi * form_factor;
}

double EmitterImportance(const EmitterShape& shape, const Vec3& x, const Vec3& n) {
  return EmitterImportance(shape, EmitterFormFactor(shape, x, n));
}

namespace {

// The bilinear warp's corner weight of a direction from x (receiver normal n) towards p.
double CosineWeight(const Vec3& x, const Vec3& n, const Vec3& p) {
  return std::max(0.01, Dot(n, Normalize(p - x)));
}

// u warped by the bilinear density with corner weights w, into `u`; returns its pdf.
double Warp(const std::array<double, 4>& w, Point2& u) {
  u = SampleBilinear(u, w);
  return BilinearPdf(u, w);
}

}  // namespace

EmitterPointSampler::EmitterPointSampler(const EmitterShape& shape, const Vec3& x, const Vec3& n)
    : shape_(shape), x_(x) {
  const std::array<Vec3, 4>& c = shape.corner;
  for (uint32_t k = 0; k < 4; ++k) weight_[k] = CosineWeight(x, n, c[k]);
  if (shape.rectangle) {
    rectangle_.emplace(SphericalRectangle{c[0], c[1] - c[0], c[3] - c[0]}, x);
  } else if (shape.corners == 4) {
    const Vec3 a = Normalize(c[0] - x), b = Normalize(c[1] - x);
    const Vec3 d = Normalize(c[2] - x), e = Normalize(c[3] - x);
    const double first = SphericalTriangleArea(a, b, d), second = SphericalTriangleArea(a, d, e);
    share_ = first + second > 0 ? first / (first + second) : -1;
  }
}

EmitterSample EmitterPointSampler::operator()(Point2 u) const {
  const std::array<Vec3, 4>& c = shape_.corner;
  const std::array<double, 4>& cw = weight_;
  EmitterSample sample;
  if (rectangle_) {
    // u.x runs from c[0] to c[1], u.y from c[0] to c[3].
    const double warp = Warp({cw[0], cw[1], cw[3], cw[2]}, u);
    sample.point = (*rectangle_)(u, &sample.pdf);
    sample.pdf *= warp;
    return sample;
  }
  // A triangle, or a quad as the triangles (0, 1, 2) and (0, 2, 3), one chosen by its share of
  // the solid angle with u.x (then rescaled to [0, 1)): uniform over the whole solid angle.
  std::array<uint32_t, 3> t = {0, 1, 2};
  double pdf_scale = 1;
  if (shape_.corners == 4) {
    if (share_ < 0) return sample;
    if (u.x < share_) {
      u.x = std::min(u.x / share_, 0x1.fffffffffffffp-1);
      pdf_scale = share_;
    } else {
      u.x = std::min((u.x - share_) / (1 - share_), 0x1.fffffffffffffp-1);
      t = {0, 2, 3};
      pdf_scale = 1 - share_;
    }
  }
  // Arvo's map takes u.y = 0 to the second vertex whatever u.x, and u.y = 1 along the arc
  // from the first vertex (u.x = 0) to the third (u.x = 1).
  const double warp = Warp({cw[t[1]], cw[t[1]], cw[t[0]], cw[t[2]]}, u);
  const Vec3 w = SampleSphericalTriangle({c[t[0]], c[t[1]], c[t[2]]}, x_, u, &sample.pdf);
  sample.pdf *= pdf_scale * warp;
  // Where the direction meets the emitter's plane.
  const double along = Dot(w, shape_.normal);
  if (!(along < 0)) {  // parallel to the plane, or towards its back: no such point
    sample.pdf = 0;
    return sample;
  }
  sample.point = x_ + w * (Dot(c[0] - x_, shape_.normal) / along);
  return sample;
}

EmitterSample SampleEmitterSolidAngle(const EmitterShape& shape, const Vec3& x, const Vec3& n,
                                      Point2 u) {
  return EmitterPointSampler(shape, x, n)(u);
}

}  // namespace radflux
