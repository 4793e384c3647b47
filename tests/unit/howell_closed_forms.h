// View factors in closed form from Howell's catalogue (A Catalog of Radiation Heat
// Transfer Configuration Factors), the references the row builders are tested against.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "solver/core/gauss_legendre.h"

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

using radflux::GaussLegendre;

namespace detail {

// u ln(u^2 + q2), 0 at u = q2 = 0.
inline double ULog(double u, double q2) {
  const double r = u * u + q2;
  return r > 0 ? u * std::log(r) : 0;
}

// int_a^b ln(u^2 + q^2) du, q >= 0.
inline double LogQuadratic(double a, double b, double q) {
  auto f = [&](double u) { return ULog(u, q * q) - 2 * u + (q > 0 ? 2 * q * std::atan(u / q) : 0); };
  return f(b) - f(a);
}

// int_0^l int_0^l ln r dy1 dy2 for two parallel, aligned segments of length l at distance d
// (d = 0: the same segment, l^2 (ln l - 3/2)).
inline double ParallelEdges(double l, double d) {
  auto f1 = [&](double u) { return ULog(u, d * d) - 2 * u + (d > 0 ? 2 * d * std::atan(u / d) : 0); };
  auto f2 = [&](double u) {
    const double r = u * u + d * d;
    return 0.5 * ((r > 0 ? r * std::log(r) : 0) - u * u);
  };
  return l * (f1(l) - f1(0)) - (f2(l) - f2(0));
}

// Intervals covering [a, b] that halve geometrically toward both ends and toward every
// break point inside, for Gauss-Legendre on integrands with (near-)singular corners there.
inline std::vector<std::pair<double, double>> GradedIntervals(double a, double b,
                                                               std::vector<double> breaks,
                                                               int levels) {
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  std::vector<std::pair<double, double>> out;
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double lo = breaks[k], hi = breaks[k + 1];
    if (!(hi > lo) || lo < a || hi > b) continue;
    const double mid = 0.5 * (lo + hi);
    for (const auto& [end, half] : {std::pair{lo, mid - lo}, std::pair{hi, mid - hi}}) {
      double t = 1;
      for (int l = 0; l < levels; ++l, t *= 0.5) {
        const double inner = l + 1 == levels ? 0 : 0.5 * t;
        double x0 = end + half * inner, x1 = end + half * t;
        if (x0 > x1) std::swap(x0, x1);
        out.emplace_back(x0, x1);
      }
    }
  }
  return out;
}

// int_0^w int_0^h ln r dxi dx for segments from a common line-point pair at angle phi,
// offset by t along the common edge: r^2 = x^2 + xi^2 - 2 x xi cos(phi) + t^2. The inner
// integral is closed form; the outer one is Gauss-Legendre on intervals graded toward
// x = 0 (the x ln x corner when t = 0) and toward x = h / cos(phi), where the foot of x
// on the other segment's line passes its end (width ~ h tan(phi): sharp as phi -> 0).
inline double ObliqueEdges(double w, double h, double phi, double t) {
  static const GaussLegendre g(16);
  const double c = std::cos(phi), s = std::sin(phi);
  std::vector<double> breaks;
  if (c > 0 && h / c < w) breaks.push_back(h / c);
  double sum = 0;
  for (const auto& [a, b] : GradedIntervals(0, w, breaks, 40)) {
    for (size_t k = 0; k < g.x.size(); ++k) {
      const double x = a + (b - a) * (g.x[k] + 1) / 2;
      const double q = std::sqrt(x * x * s * s + t * t);
      sum += g.w[k] * (b - a) / 2 * 0.5 * LogQuadratic(-x * c, h - x * c, q);
    }
  }
  return sum;
}

}  // namespace detail

// Howell's "two finite rectangles of the same length l with a common edge at angle phi"
// (C-15 in the numbering issue 6 cites; C-17 in the web catalogue): from rectangle 1
// (w x l) to rectangle 2 (h x l), both facing into the wedge of opening angle phi
// (radians, 0 < phi < pi). Howell's entry is closed form except for one 1D integral. We
// evaluate it from its derivation, Stokes' double contour integral
//   A_1 F_12 = (1 / 2 pi) sum over edge pairs (e1 . e2) int int ln r ds1 ds2,
// where only edges along the common direction (parallel pairs, closed form above, the
// common edge against itself included) and the edges across it (oblique pairs,
// e1 . e2 = cos phi, one closed-form integral and one Gauss quadrature) contribute. At
// 90 degrees the oblique terms vanish and this is C-14 exactly (checked in a test to 1e-12).
inline double AngledRectangles(double w, double h, double l, double phi) {
  const double d = std::sqrt(std::max(0.0, w * w + h * h - 2 * w * h * std::cos(phi)));
  const double parallel = -detail::ParallelEdges(l, 0) + detail::ParallelEdges(l, h) +
                          detail::ParallelEdges(l, w) - detail::ParallelEdges(l, d);
  const double oblique = 2 * std::cos(phi) *
                         (detail::ObliqueEdges(w, h, phi, l) - detail::ObliqueEdges(w, h, phi, 0));
  return 0.5 * (parallel + oblique) / (std::numbers::pi * w * l);
}

}  // namespace radflux::testing
