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

void SetEmitterBounds(EmitterShape& shape) {
  shape.centre = {};
  for (uint32_t k = 0; k < shape.corners; ++k) shape.centre += shape.corner[k];
  shape.centre = shape.centre / shape.corners;
  double radius2 = 0;
  for (uint32_t k = 0; k < shape.corners; ++k) {
    const Vec3 d = shape.corner[k] - shape.centre;
    radius2 = std::max(radius2, Dot(d, d));
  }
  shape.radius = std::sqrt(radius2);
}

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
  SetEmitterBounds(shape);
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

double FarEmitterImportance(std::span<const Vec3> corners, const Vec3& normal, double power,
                            const Vec3& x, const Vec3& n) {
  if (!(Dot(x - corners[0], normal) > 0)) return 0;  // x sees the back side
  double sum = 0;
  for (const Vec3& c : corners) {
    const Vec3 d = c - x;
    const double r2 = Dot(d, d);
    sum += std::max(0.0, Dot(n, d)) * -Dot(normal, d) / (r2 * r2);
  }
  return power * sum / static_cast<double>(corners.size());
}

EmitterReach ReachOf(const EmitterShape& shape, const Vec3& x) {
  const Vec3 d = shape.centre - x;
  const double distance2 = Dot(d, d);
  if (!(distance2 >= kFarRadii * kFarRadii * shape.radius * shape.radius)) return {};
  const double height = std::abs(Dot(x - shape.corner[0], shape.normal));
  const double nearest = std::max(height, std::sqrt(distance2) - shape.radius);
  return {true, shape.area * height / (std::numbers::pi * nearest * nearest * nearest)};
}

namespace {

// The unoccluded integrand cos_x cos_y / r^2 of the form factor at point p of the emitter
// (unit normal m) from x (unit normal n); 0 where either cosine is not positive.
double Integrand(const Vec3& x, const Vec3& n, const Vec3& p, const Vec3& m) {
  const Vec3 d = p - x;
  const double r2 = Dot(d, d);
  return std::max(0.0, Dot(n, d)) * std::max(0.0, -Dot(m, d)) / (r2 * r2);
}

// `w` raised to at least 0.01 of its largest (all of them 1 when none is positive).
std::array<double, 4> Floored(std::array<double, 4> w) {
  const double top = std::max({w[0], w[1], w[2], w[3]});
  for (double& v : w) v = top > 0 ? std::max(v, 0.01 * top) : 1;
  return w;
}

}  // namespace

EmitterPointSampler::EmitterPointSampler(const EmitterShape& shape, const Vec3& x, const Vec3& n)
    : shape_(shape), x_(x), far_(ReachOf(shape, x).far) {
  const std::array<Vec3, 4>& c = shape.corner;
  if (far_) {
    // The integrand at the corners: in ByArea's u a rectangle's corners 0, 1, 3, 2 lie at
    // (0,0), (1,0), (0,1), (1,1); a triangle's are ordered there as it samples.
    const auto f = [&](const Vec3& p) { return Integrand(x, n, p, shape.normal); };
    if (shape.rectangle) {
      weight_ = Floored({f(c[0]), f(c[1]), f(c[3]), f(c[2])});
    } else if (shape.corners == 4) {
      share_ = shape.area > 0 ? 0.5 * Length(Cross(c[1] - c[0], c[2] - c[0])) / shape.area : -1;
    }
    if (!shape.rectangle) weight_ = {f(c[0]), f(c[1]), f(c[2]), f(c[3])};  // per half, below
    return;
  }
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

EmitterSample EmitterPointSampler::ByArea(Point2 u) const {
  const std::array<Vec3, 4>& c = shape_.corner;
  const std::array<double, 4>& f = weight_;
  EmitterSample sample;
  double pdf_area;
  if (shape_.rectangle) {
    const double warp = Warp(f, u);
    sample.point = c[0] + (c[1] - c[0]) * u.x + (c[3] - c[0]) * u.y;
    pdf_area = warp / shape_.area;
  } else {
    // A triangle, or a quad's half (0, 1, 2) or (0, 2, 3) chosen by u.x with its share of
    // the area; Heitz's map takes u's corners (0,0), (1,0), (0,1), (1,1) to its corners 2, 0,
    // 1 and the middle of 0-1.
    std::array<uint32_t, 3> t = {0, 1, 2};
    if (shape_.corners == 4) {
      if (!(share_ > 0 && share_ < 1)) return sample;
      if (u.x < share_) {
        u.x = std::min(u.x / share_, 0x1.fffffffffffffp-1);
      } else {
        u.x = std::min((u.x - share_) / (1 - share_), 0x1.fffffffffffffp-1);
        t = {0, 2, 3};
      }
    }
    const double warp = Warp(Floored({f[t[2]], f[t[0]], f[t[1]], 0.5 * (f[t[0]] + f[t[1]])}), u);
    const auto [b0, b1] = SampleUniformTriangle(u);
    sample.point = c[t[0]] * b0 + c[t[1]] * b1 + c[t[2]] * (1 - b0 - b1);
    pdf_area = warp / shape_.area;  // the half's chance times warp / its area
  }
  // Per steradian at x: r^2 / cos_y per unit area.
  const Vec3 d = sample.point - x_;
  const double r2 = Dot(d, d);
  const double cos_y = -Dot(shape_.normal, d) / std::sqrt(r2);
  sample.pdf = cos_y > 0 ? pdf_area * r2 / cos_y : 0;
  return sample;
}

EmitterSample EmitterPointSampler::operator()(Point2 u) const {
  if (far_) return ByArea(u);
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
