#include "solver/formfactor/surface_pair_integrator.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "solver/core/gauss_legendre.h"
#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

// The integrand: F from a differential area at x on i to all of j.
struct Integrand {
  const SurfaceShape& i;
  const SurfaceShape& j;
  bool j_in_front;  // all of j in front of i's plane: no per-point clipping needed
  uint64_t& evaluations;

  double operator()(const Vec3& x) const {
    ++evaluations;
    return j_in_front ? UnclippedPointToPolygonFormFactor(x, i.normal, j.polygon)
                      : PointToPolygonFormFactor(x, i.normal, j.polygon);
  }
};

double TriangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * Length(Cross(b - a, c - a));
}

// Gauss-Legendre nodes and weights on [0, 1] for n points (n <= kMaxGauss).
constexpr int kMaxGauss = 4;
struct GaussRule {
  double x[kMaxGauss], w[kMaxGauss];
};
GaussRule MakeGaussRule(int n) {
  const GaussLegendre legendre(n);
  GaussRule rule{};
  for (int i = 0; i < n; ++i) {
    rule.x[i] = 0.5 * (1 - legendre.x[i]);
    rule.w[i] = 0.5 * legendre.w[i];
  }
  return rule;
}
const GaussRule& Gauss(int n) {
  static const GaussRule rules[kMaxGauss + 1] = {GaussRule{}, MakeGaussRule(1), MakeGaussRule(2),
                                                 MakeGaussRule(3), MakeGaussRule(4)};
  return rules[n];
}

// A piece of i: a triangle (c[3] unused) or a convex quadrilateral, bilinearly mapped.
struct Cell {
  Vec3 c[4];
  bool quad = false;

  // n x n Gauss points: a quad through its bilinear map, a triangle through Duffy's
  // collapse of the square (x = a + u (b - a) + u v (c - b), Jacobian 2 A u).
  double Integrate(const Integrand& f, int n) const {
    const GaussRule& g = Gauss(n);
    double sum = 0;
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        const double u = g.x[a], v = g.x[b];
        Vec3 x, du, dv;
        if (quad) {
          x = c[0] * ((1 - u) * (1 - v)) + c[1] * (u * (1 - v)) + c[2] * (u * v) + c[3] * ((1 - u) * v);
          du = (c[1] - c[0]) * (1 - v) + (c[2] - c[3]) * v;
          dv = (c[3] - c[0]) * (1 - u) + (c[2] - c[1]) * u;
        } else {
          x = c[0] + (c[1] - c[0]) * u + (c[2] - c[1]) * (u * v);
          du = (c[1] - c[0]) + (c[2] - c[1]) * v;
          dv = (c[2] - c[1]) * u;
        }
        sum += g.w[a] * g.w[b] * Length(Cross(du, dv)) * f(x);
      }
    }
    return sum;
  }

  // The four children split at the edge midpoints.
  void Split(Cell (&out)[4]) const {
    if (quad) {
      const Vec3 m01 = (c[0] + c[1]) * 0.5, m12 = (c[1] + c[2]) * 0.5, m23 = (c[2] + c[3]) * 0.5,
                 m30 = (c[3] + c[0]) * 0.5, mid = (m01 + m23) * 0.5;
      out[0] = {{c[0], m01, mid, m30}, true};
      out[1] = {{m01, c[1], m12, mid}, true};
      out[2] = {{mid, m12, c[2], m23}, true};
      out[3] = {{m30, mid, m23, c[3]}, true};
      return;
    }
    const Vec3 ab = (c[0] + c[1]) * 0.5, bc = (c[1] + c[2]) * 0.5, ca = (c[2] + c[0]) * 0.5;
    out[0] = {{c[0], ab, ca, {}}, false};
    out[1] = {{ab, c[1], bc, {}}, false};
    out[2] = {{ca, bc, c[2], {}}, false};
    out[3] = {{bc, ca, ab, {}}, false};
  }
};

// The integral of f over the cell: 2 x 2 and 3 x 3 Gauss rules; split where they disagree.
double Adaptive(const Integrand& f, const Cell& cell, const PairIntegration& options, int depth) {
  const double coarse = cell.Integrate(f, 2), fine = cell.Integrate(f, 3);
  if (depth >= options.max_depth ||
      std::abs(fine - coarse) <= options.tolerance * std::abs(fine) + 1e-15) {
    return fine;
  }
  Cell children[4];
  cell.Split(children);
  double sum = 0;
  for (const Cell& child : children) sum += Adaptive(f, child, options, depth + 1);
  return sum;
}

// Calls visit(cell) for the region of i as cells: the polygon itself when it is a triangle
// or quadrilateral, else a fan of triangles. Allocates nothing.
template <typename Visit>
void ForEachCell(std::span<const Vec3> polygon, Visit&& visit) {
  if (polygon.size() == 4) {
    visit(Cell{{polygon[0], polygon[1], polygon[2], polygon[3]}, true});
    return;
  }
  for (size_t k = 1; k + 1 < polygon.size(); ++k) {
    visit(Cell{{polygon[0], polygon[k], polygon[k + 1], {}}, false});
  }
}

}  // namespace

void PairCounts::Merge(const PairCounts& o) {
  culled += o.culled;
  one_point += o.one_point;
  middle += o.middle;
  adaptive += o.adaptive;
  evaluations += o.evaluations;
}

SurfaceShape MakeSurfaceShape(std::vector<Vec3> polygon) {
  SurfaceShape s;
  Vec3 newell;
  for (size_t k = 0; k < polygon.size(); ++k) {
    newell += Cross(polygon[k], polygon[(k + 1) % polygon.size()]);
  }
  s.area = Length(newell) / 2;
  s.normal = newell / Length(newell);
  s.lo = s.hi = polygon[0];
  for (size_t k = 1; k + 1 < polygon.size(); ++k) {  // fan triangles from vertex 0
    const double a = TriangleArea(polygon[0], polygon[k], polygon[k + 1]);
    s.centroid += (polygon[0] + polygon[k] + polygon[k + 1]) * (a / 3);
  }
  s.centroid = s.centroid / s.area;
  for (const Vec3& p : polygon) {
    s.lo = {std::min(s.lo.x, p.x), std::min(s.lo.y, p.y), std::min(s.lo.z, p.z)};
    s.hi = {std::max(s.hi.x, p.x), std::max(s.hi.y, p.y), std::max(s.hi.z, p.z)};
    for (const Vec3& q : polygon) s.diameter = std::max(s.diameter, Length(p - q));
  }
  for (const Vec3& p : polygon) s.flatness = std::max(s.flatness, std::abs(Dot(p - s.centroid, s.normal)));
  s.polygon = std::move(polygon);
  return s;
}

double CoplanarBand(const SurfaceShape& a, const SurfaceShape& b) {
  return 2 * (a.flatness + b.flatness) + kCoplanarRelative * (a.diameter + b.diameter);
}

bool PartlyInFront(const SurfaceShape& a, const SurfaceShape& b) {
  const double band = CoplanarBand(a, b);
  for (const Vec3& p : b.polygon) {
    if (Dot(p - a.centroid, a.normal) > band) return true;
  }
  return false;
}

bool PartlyBehind(const SurfaceShape& a, const SurfaceShape& b) {
  const double band = CoplanarBand(a, b);
  for (const Vec3& p : b.polygon) {
    if (Dot(p - a.centroid, a.normal) < -band) return true;
  }
  return false;
}

bool CanSeeEachOther(const SurfaceShape& i, const SurfaceShape& j) {
  return PartlyInFront(i, j) && PartlyInFront(j, i);
}

namespace {

// Where b lies for a's plane, beyond the band: partly in front (some vertex above +band), and
// wholly in front (no vertex below -band). One pass for CanSeeEachOther's test and the
// integration's choice.
struct Side {
  bool partly = false, wholly = true;
};
Side SideOf(const SurfaceShape& a, const SurfaceShape& b, double band) {
  Side side;
  for (const Vec3& p : b.polygon) {
    const double d = Dot(p - a.centroid, a.normal);
    side.partly = side.partly || d > band;
    side.wholly = side.wholly && d >= -band;
  }
  return side;
}

}  // namespace

double UnoccludedViewFactor(const SurfaceShape& i, const SurfaceShape& j,
                            const PairIntegration& options, PairCounts& counts) {
  const double band = CoplanarBand(i, j);
  const Side j_side = SideOf(i, j, band);
  const Side i_side = j_side.partly ? SideOf(j, i, band) : Side{};
  if (!j_side.partly || !i_side.partly) {  // !CanSeeEachOther(i, j)
    ++counts.culled;
    return 0;
  }
  const bool j_in_front = j_side.wholly, i_in_front = i_side.wholly;
  const Integrand f{i, j, j_in_front, counts.evaluations};
  const double gap = std::max(Length(j.centroid - i.centroid) - 0.5 * j.diameter, 0.0);
  if (i_in_front && gap >= options.far_ratio * i.diameter) {
    ++counts.one_point;
    return std::clamp(f(i.centroid), 0.0, 1.0);
  }
  if (i_in_front && gap >= options.middle_ratio * i.diameter) {
    ++counts.middle;
    double integral = 0;
    ForEachCell(i.polygon, [&](const Cell& cell) { integral += cell.Integrate(f, 2); });
    return std::clamp(integral / i.area, 0.0, 1.0);
  }
  ++counts.adaptive;
  // The part of i in front of j's plane.
  const std::vector<Vec3> region =
      i_in_front ? i.polygon : ClipPolygonToHalfSpace(i.polygon, j.centroid, j.normal);
  double integral = 0;
  ForEachCell(region, [&](const Cell& cell) { integral += Adaptive(f, cell, options, 0); });
  return std::clamp(integral / i.area, 0.0, 1.0);
}

}  // namespace radflux
