#include "solver/core/inverse_bilinear.h"

#include <algorithm>
#include <cmath>

namespace radflux {

std::pair<double, double> InverseBilinear(const std::array<Vec3, 4>& v, const Vec3& normal,
                                          const Vec3& point) {
  const Frame frame = Frame::FromNormal(normal);
  auto flat = [&](const Vec3& d) {
    return std::array<double, 2>{Dot(d, frame.s), Dot(d, frame.t)};
  };
  auto cross = [](const std::array<double, 2>& a, const std::array<double, 2>& b) {
    return a[0] * b[1] - a[1] * b[0];
  };
  const auto e = flat(v[1] - v[0]), f = flat(v[3] - v[0]), h = flat(point - v[0]);
  const auto g = flat(v[0] - v[1] + v[2] - v[3]);
  const double a = -cross(e, g), b = cross(h, g) - cross(e, f), c = cross(h, f);
  const double root = std::sqrt(std::max(0.0, b * b - 4 * a * c));
  const double q = -0.5 * (b + std::copysign(root, b));
  auto outside = [](double x) { return std::isfinite(x) ? std::max(-x, x - 1) : 1e300; };
  const double first = q != 0 ? c / q : 0, second = a != 0 ? q / a : 1e300;
  const double s = std::clamp(outside(first) <= outside(second) ? first : second, 0.0, 1.0);
  const std::array<double, 2> along = {f[0] + s * g[0], f[1] + s * g[1]};
  const double length2 = along[0] * along[0] + along[1] * along[1];
  const double t =
      length2 > 0 ? ((h[0] - s * e[0]) * along[0] + (h[1] - s * e[1]) * along[1]) / length2 : 0;
  return {s, std::clamp(t, 0.0, 1.0)};
}

}  // namespace radflux
