// GaussLegendre: n-point Gauss-Legendre quadrature on [-1, 1] (nodes by Newton's method on the
// Legendre recurrence), exact for polynomials of degree < 2n. Used by the view-factor pair
// integrator and by the tests' closed forms.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

namespace radflux {

struct GaussLegendre {
  std::vector<double> x, w;  // nodes in (-1, 1), descending, and their weights (sum 2)

  explicit GaussLegendre(int n) {
    for (int i = 1; i <= n; ++i) {
      double z = std::cos(std::numbers::pi * (i - 0.25) / (n + 0.5)), dp = 1;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x.push_back(z);
      w.push_back(2 / ((1 - z * z) * dp * dp));
    }
  }
};

}  // namespace radflux
