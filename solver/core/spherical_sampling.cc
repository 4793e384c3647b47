#include "solver/core/spherical_sampling.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace radflux {
namespace {

// Below this solid angle (sr) the spherical maps lose digits to cancellation (their angles
// sum to pi or 2 pi within the solid angle); there the samplers take points uniform in area
// instead, with the exact pdf per steradian r^2 / (A cos), so the pair stays consistent.
constexpr double kTinySolidAngle = 1e-9;

double AngleBetween(const Vec3& a, const Vec3& b) {
  // Accurate near 0 and pi, unlike acos of the dot product.
  return 2 * std::atan2(Length(a - b), Length(a + b));
}

// The part of v orthogonal to unit w, normalised (v not parallel to w).
Vec3 OrthogonalUnit(const Vec3& v, const Vec3& w) { return Normalize(v - w * Dot(v, w)); }

// pdf per steradian at p of a point q on a planar polygon of area `area` and unit normal n,
// sampled uniformly by area.
double AreaToSolidAnglePdf(const Vec3& p, const Vec3& q, const Vec3& n, double area) {
  const Vec3 d = q - p;
  const double r2 = Dot(d, d);
  const double cosine = std::abs(Dot(n, d)) / std::sqrt(r2);
  return cosine > 0 ? r2 / (area * cosine) : 0;
}

}  // namespace

double SphericalTriangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double numerator = std::abs(Dot(a, Cross(b, c)));
  const double denominator = 1 + Dot(a, b) + Dot(b, c) + Dot(c, a);
  return 2 * std::atan2(numerator, denominator);
}

Vec3 SampleSphericalTriangle(const std::array<Vec3, 3>& v, const Vec3& p, Point2 u, double* pdf) {
  const Vec3 a = Normalize(v[0] - p), b = Normalize(v[1] - p), c = Normalize(v[2] - p);
  const double area = SphericalTriangleArea(a, b, c);
  if (pdf) *pdf = 0;
  if (!(area > 0)) return a;
  if (area < kTinySolidAngle) {
    const auto [b0, b1] = SampleUniformTriangle(u);
    const Vec3 q = v[0] * b0 + v[1] * b1 + v[2] * (1 - b0 - b1);
    const Vec3 n = Cross(v[1] - v[0], v[2] - v[0]);
    if (pdf) *pdf = AreaToSolidAnglePdf(p, q, Normalize(n), Length(n) / 2);
    return Normalize(q - p);
  }
  if (pdf) *pdf = 1 / area;
  // Arvo: choose the sub-triangle (a, b, c_hat) of area u.x * area, with c_hat on the arc
  // from a to c, then a point on the arc from b to c_hat by u.y.
  const double alpha = AngleBetween(Normalize(Cross(a, b)), Normalize(Cross(a, c)));
  const double sub_area = u.x * area;
  const double s = std::sin(sub_area - alpha), t = std::cos(sub_area - alpha);
  const double cos_alpha = std::cos(alpha), sin_alpha = std::sin(alpha);
  const double uu = t - cos_alpha;
  const double vv = s + sin_alpha * Dot(a, b);
  const double denominator = (vv * s + uu * t) * sin_alpha;
  double q = denominator != 0 ? ((vv * t - uu * s) * cos_alpha - vv) / denominator : 1;
  q = std::clamp(q, -1.0, 1.0);
  const Vec3 c_hat = a * q + OrthogonalUnit(c, a) * std::sqrt(1 - q * q);
  const double z = 1 - u.y * (1 - Dot(c_hat, b));
  const double b_c_hat = Dot(c_hat, b);
  if (b_c_hat >= 1) return b;  // the arc from b to c_hat is a point
  return b * z + OrthogonalUnit(c_hat, b) * std::sqrt(std::max(0.0, 1 - z * z));
}

Point2 InvertSphericalTriangleSample(const std::array<Vec3, 3>& v, const Vec3& p, const Vec3& w) {
  const Vec3 a = Normalize(v[0] - p), b = Normalize(v[1] - p), c = Normalize(v[2] - p);
  const double area = SphericalTriangleArea(a, b, c);
  if (area < kTinySolidAngle) {
    // The point where w meets the triangle's plane, in barycentrics.
    const Vec3 e1 = v[1] - v[0], e2 = v[2] - v[0], n = Cross(e1, e2);
    const Vec3 q = p + w * (Dot(v[0] - p, n) / Dot(w, n));
    const double n2 = Dot(n, n);
    const double b1 = Dot(Cross(q - v[0], e2), n) / n2;
    const double b2 = Dot(Cross(e1, q - v[0]), n) / n2;
    return InvertUniformTriangleSample(1 - b1 - b2, b1);
  }
  // c_hat: where the great circle through b and w meets the arc from a to c.
  Vec3 c_hat = Normalize(Cross(Cross(b, w), Cross(c, a)));
  if (Dot(c_hat, a + c) < 0) c_hat = -c_hat;
  const double u0 = SphericalTriangleArea(a, b, c_hat) / area;
  const double arc = 1 - Dot(c_hat, b);
  const double u1 = arc > 0 ? (1 - Dot(w, b)) / arc : 0;
  return {std::clamp(u0, 0.0, 1.0), std::clamp(u1, 0.0, 1.0)};
}

namespace {

SphericalRectangleFrame MakeRectangleFrame(const SphericalRectangle& rect, const Vec3& p) {
  SphericalRectangleFrame f;
  const double ex_length = Length(rect.ex), ey_length = Length(rect.ey);
  f.x = rect.ex / ex_length;
  f.y = rect.ey / ey_length;
  f.z = Cross(f.x, f.y);
  const Vec3 d = rect.s - p;
  f.x0 = Dot(d, f.x);
  f.y0 = Dot(d, f.y);
  f.z0 = Dot(d, f.z);
  if (f.z0 > 0) {
    f.z = -f.z;
    f.z0 = -f.z0;
  }
  f.x1 = f.x0 + ex_length;
  f.y1 = f.y0 + ey_length;
  const Vec3 v00(f.x0, f.y0, f.z0), v01(f.x0, f.y1, f.z0);
  const Vec3 v10(f.x1, f.y0, f.z0), v11(f.x1, f.y1, f.z0);
  const Vec3 n0 = Normalize(Cross(v00, v10)), n1 = Normalize(Cross(v10, v11));
  const Vec3 n2 = Normalize(Cross(v11, v01)), n3 = Normalize(Cross(v01, v00));
  const double g0 = AngleBetween(-n0, n1), g1 = AngleBetween(-n1, n2);
  const double g2 = AngleBetween(-n2, n3), g3 = AngleBetween(-n3, n0);
  f.b0 = n0.z;
  f.b1 = n2.z;
  f.k = 2 * std::numbers::pi - g2 - g3;
  f.solid_angle = g0 + g1 - f.k;
  return f;
}

// u.y's coordinate h(y) = y / sqrt(d^2 + y^2) along the strip at x-distance d.
double StripCoordinate(double y, double d2) { return y / std::sqrt(d2 + y * y); }

}  // namespace

double SphericalRectangleSolidAngle(const SphericalRectangle& rect, const Vec3& p) {
  const Vec3 a = Normalize(rect.s - p), b = Normalize(rect.s + rect.ex - p);
  const Vec3 c = Normalize(rect.s + rect.ex + rect.ey - p), d = Normalize(rect.s + rect.ey - p);
  return SphericalTriangleArea(a, b, c) + SphericalTriangleArea(a, c, d);
}

SphericalRectangleSampler::SphericalRectangleSampler(const SphericalRectangle& rect, const Vec3& p)
    : rect_(rect), p_(p), solid_angle_(SphericalRectangleSolidAngle(rect, p)) {
  if (solid_angle_ >= kTinySolidAngle) frame_ = MakeRectangleFrame(rect, p);
}

Vec3 SphericalRectangleSampler::operator()(Point2 u, double* pdf) const {
  const SphericalRectangle& rect = rect_;
  const Vec3& p = p_;
  const Vec3 area_point = rect.s + rect.ex * u.x + rect.ey * u.y;
  if (pdf) *pdf = 0;
  if (!(solid_angle_ > 0)) return area_point;
  if (solid_angle_ < kTinySolidAngle) {
    const Vec3 n = Cross(rect.ex, rect.ey);
    if (pdf) *pdf = AreaToSolidAnglePdf(p, area_point, Normalize(n), Length(n));
    return area_point;
  }
  const SphericalRectangleFrame& f = frame_;
  if (pdf) *pdf = 1 / f.solid_angle;
  // u.x picks the x where the sub-rectangle [x0, x] has solid angle u.x * S...
  const double au = u.x * f.solid_angle + f.k;
  const double fu = (std::cos(au) * f.b0 - f.b1) / std::sin(au);
  const double cu =
      std::clamp(std::copysign(1 / std::sqrt(fu * fu + f.b0 * f.b0), fu), -1 + 1e-15, 1 - 1e-15);
  const double xu = std::clamp(-(cu * f.z0) / std::sqrt(1 - cu * cu), f.x0, f.x1);
  // ...and u.y the y along that strip, uniform in h(y).
  const double d2 = xu * xu + f.z0 * f.z0;
  const double h0 = StripCoordinate(f.y0, d2), h1 = StripCoordinate(f.y1, d2);
  const double hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
  const double yv = hv2 < 1 ? std::clamp(hv * std::sqrt(d2 / (1 - hv2)), f.y0, f.y1) : f.y1;
  return p + f.x * xu + f.y * yv + f.z * f.z0;
}

Vec3 SampleSphericalRectangle(const SphericalRectangle& rect, const Vec3& p, Point2 u,
                              double* pdf) {
  return SphericalRectangleSampler(rect, p)(u, pdf);
}

Point2 InvertSphericalRectangleSample(const SphericalRectangle& rect, const Vec3& p,
                                      const Vec3& q) {
  const double solid_angle = SphericalRectangleSolidAngle(rect, p);
  const Vec3 local = q - rect.s;
  const double a = Dot(local, rect.ex) / Dot(rect.ex, rect.ex);
  const double b = Dot(local, rect.ey) / Dot(rect.ey, rect.ey);
  if (solid_angle < kTinySolidAngle) return {std::clamp(a, 0.0, 1.0), std::clamp(b, 0.0, 1.0)};
  const SphericalRectangleFrame f = MakeRectangleFrame(rect, p);
  // u.x: the solid angle of the sub-rectangle [0, a] x [0, 1] over the whole one's.
  const SphericalRectangle sub{rect.s, rect.ex * std::clamp(a, 0.0, 1.0), rect.ey};
  const double u0 = SphericalRectangleSolidAngle(sub, p) / f.solid_angle;
  // u.y: h along the strip through q, as a fraction of the strip's range.
  const double xu = Dot(q - p, f.x), yv = Dot(q - p, f.y);
  const double d2 = xu * xu + f.z0 * f.z0;
  const double h0 = StripCoordinate(f.y0, d2), h1 = StripCoordinate(f.y1, d2);
  const double u1 = h1 > h0 ? (StripCoordinate(yv, d2) - h0) / (h1 - h0) : b;
  return {std::clamp(u0, 0.0, 1.0), std::clamp(u1, 0.0, 1.0)};
}

}  // namespace radflux
