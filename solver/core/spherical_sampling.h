// Sampling the solid angle a planar polygon subtends at a point, in pairs with their
// inverse and pdf (after pbrt-v4's util/sampling.h): spherical triangles by Arvo's method
// (Arvo 1995, "Stratified Sampling of Spherical Triangles") and spherical rectangles by
// Urena, Fajardo and King's area-preserving parametrisation (EGSR 2013). Both maps take the
// unit square onto the polygon's solid angle with constant Jacobian, so a stratified u gives
// stratified directions and the pdf (per steradian) is 1 / solid angle.
#pragma once

#include <array>

#include "solver/core/sampling.h"
#include "solver/core/vec3.h"

namespace radflux {

// Solid angle (sr) of the spherical triangle with unit vertices a, b, c (Van Oosterom and
// Strackee's formula; accurate for tiny triangles too). In [0, 2 pi].
double SphericalTriangleArea(const Vec3& a, const Vec3& b, const Vec3& c);

// A direction (unit) from p, uniform in the solid angle of triangle v as seen from p, for u
// in [0,1)^2. *pdf (when given) is 1 / solid angle, or 0 when the triangle subtends no
// solid angle (degenerate, or p in its plane); then the direction is towards v[0].
Vec3 SampleSphericalTriangle(const std::array<Vec3, 3>& v, const Vec3& p, Point2 u,
                             double* pdf = nullptr);
// The u that SampleSphericalTriangle maps to direction w (unit, inside the triangle's cone).
Point2 InvertSphericalTriangleSample(const std::array<Vec3, 3>& v, const Vec3& p, const Vec3& w);

// The rectangle s + a ex + b ey, (a, b) in [0,1]^2, with ex and ey orthogonal.
struct SphericalRectangle {
  Vec3 s, ex, ey;
};

// Solid angle (sr) of `rect` seen from p (0 when p is in its plane).
double SphericalRectangleSolidAngle(const SphericalRectangle& rect, const Vec3& p);
// A point on `rect`, uniform in the solid angle it subtends at p, for u in [0,1)^2 (u.x
// sweeps the ex side, u.y the ey side). *pdf (when given) is 1 / solid angle per steradian,
// 0 when the rectangle subtends no solid angle (then the point is s + u.x ex + u.y ey).
Vec3 SampleSphericalRectangle(const SphericalRectangle& rect, const Vec3& p, Point2 u,
                              double* pdf = nullptr);
// Urena et al.'s set-up of a rectangle seen from p: p's frame (x along ex, y along ey, z
// away from the rectangle), the rectangle's extent [x0, x1] x [y0, y1] at depth z0 < 0, and
// the constants of the u.x map.
struct SphericalRectangleFrame {
  Vec3 x, y, z;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0, z0 = 0;
  double b0 = 0, b1 = 0, k = 0, solid_angle = 0;
};

// SampleSphericalRectangle for many u at one rectangle and point: the set-up (solid angle,
// frame) is done once, and each sample is SampleSphericalRectangle's, bit for bit.
class SphericalRectangleSampler {
 public:
  SphericalRectangleSampler(const SphericalRectangle& rect, const Vec3& p);
  Vec3 operator()(Point2 u, double* pdf = nullptr) const;

 private:
  SphericalRectangle rect_;
  Vec3 p_;
  double solid_angle_;
  SphericalRectangleFrame frame_;
};

// The u that SampleSphericalRectangle maps to point q on `rect`.
Point2 InvertSphericalRectangleSample(const SphericalRectangle& rect, const Vec3& p, const Vec3& q);

}  // namespace radflux
