// View factors in closed form from Howell's catalogue (A Catalog of Radiation Heat
// Transfer Configuration Factors), the references the row builders are tested against.
#pragma once

#include <cmath>
#include <numbers>

namespace radflux::testing {

// C-11: identical, parallel, directly opposed rectangles a x b at distance c.
inline double ParallelRectangles(double a, double b, double c) {
  const double x = a / c, y = b / c, pi = std::numbers::pi;
  const double x1 = std::sqrt(1 + x * x), y1 = std::sqrt(1 + y * y);
  return 2 / (pi * x * y) *
         (std::log(std::sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y))) +
          x * y1 * std::atan(x / y1) + y * x1 * std::atan(y / x1) - x * std::atan(x) -
          y * std::atan(y));
}

// C-14: from rectangle 1 (w x l) to rectangle 2 (h x l), perpendicular, sharing the edge l.
inline double PerpendicularRectangles(double w, double h, double l) {
  const double W = w / l, H = h / l, pi = std::numbers::pi;
  const double w2 = W * W, h2 = H * H, s = std::sqrt(h2 + w2);
  const double a = (1 + w2) * (1 + h2) / (1 + w2 + h2);
  const double b = w2 * (1 + w2 + h2) / ((1 + w2) * (w2 + h2));
  const double c = h2 * (1 + h2 + w2) / ((1 + h2) * (h2 + w2));
  return 1 / (pi * W) *
         (W * std::atan(1 / W) + H * std::atan(1 / H) - s * std::atan(1 / s) +
          0.25 * (std::log(a) + w2 * std::log(b) + h2 * std::log(c)));
}

// C-41: coaxial parallel discs, from radius r1 to radius r2 at distance h.
inline double CoaxialDiscs(double r1, double r2, double h) {
  const double R1 = r1 / h, R2 = r2 / h;
  const double X = 1 + (1 + R2 * R2) / (R1 * R1);
  return 0.5 * (X - std::sqrt(X * X - 4 * (R2 / R1) * (R2 / R1)));
}

// B-3: differential area to a parallel rectangle a x b at distance c, the normal through
// one corner of the rectangle.
inline double PointToCornerRectangle(double a, double b, double c) {
  const double A = a / c, B = b / c;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * std::numbers::pi);
}

}  // namespace radflux::testing
