#include "solver/formfactor/polygon_form_factor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace radflux {

size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, std::span<const double> distance,
                              std::span<Vec3> out) {
  size_t count = 0;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const size_t next = (k + 1) % polygon.size();
    const Vec3& a = polygon[k];
    const Vec3& b = polygon[next];
    const double da = distance[k], db = distance[next];
    if (da >= 0) out[count++] = a;
    if ((da >= 0) != (db >= 0)) out[count++] = a + (b - a) * (da / (da - db));
  }
  return count;
}

size_t ClipPolygonToHalfSpace(std::span<const Vec3> polygon, const Vec3& origin, const Vec3& n,
                              std::span<Vec3> out) {
  std::array<double, kMaxClipVertices> distance;
  for (size_t k = 0; k < polygon.size(); ++k) distance[k] = Dot(polygon[k] - origin, n);
  return ClipPolygonToHalfSpace(polygon, std::span<const double>(distance.data(), polygon.size()),
                                out);
}

std::vector<Vec3> ClipPolygonToHalfSpace(std::span<const Vec3> polygon, const Vec3& origin,
                                         const Vec3& n) {
  std::vector<double> distance;
  for (const Vec3& p : polygon) distance.push_back(Dot(p - origin, n));
  std::vector<Vec3> out(2 * polygon.size());
  out.resize(ClipPolygonToHalfSpace(polygon, distance, out));
  return out;
}

namespace {

// Two lanes of doubles (SSE2, part of every x86-64): each operation is the scalar one per
// lane, so a lane's result has the scalar code's bits.
using Double2 = double __attribute__((vector_size(16)));

// ContourEdgeTerm for the four edges (v[k], v[k + 1]), k < 4, at once into t: all on the
// small-angle path with the same operations in the same order (two lanes at a time, the two
// pairs side by side for the processor to overlap), else each on its own.
void FourContourEdgeTerms(const Vec3 (&v)[5], const Vec3& n, double (&t)[4]) {
  Double2 cx[2], cy[2], cz[2], d[2], c2[2];
  bool small = true;
  for (int h = 0; h < 2; ++h) {
    const Vec3 &a0 = v[2 * h], &a1 = v[2 * h + 1], &b1 = v[2 * h + 2];
    const Double2 ax = {a0.x, a1.x}, ay = {a0.y, a1.y}, az = {a0.z, a1.z};
    const Double2 bx = {a1.x, b1.x}, by = {a1.y, b1.y}, bz = {a1.z, b1.z};
    cx[h] = ay * bz - az * by;
    cy[h] = az * bx - ax * bz;
    cz[h] = ax * by - ay * bx;
    d[h] = ax * bx + ay * by + az * bz;
    c2[h] = cx[h] * cx[h] + cy[h] * cy[h] + cz[h] * cz[h];
    for (int l = 0; l < 2; ++l) {
      small = small && d[h][l] > 0 && c2[h][l] < kSmallAngleTan2 * (d[h][l] * d[h][l]);
    }
  }
  if (!small) {
    for (int k = 0; k < 4; ++k) t[k] = ContourEdgeTerm(v[k], v[k + 1], n);
    return;
  }
  for (int h = 0; h < 2; ++h) {
    const Double2 inv_d = 1.0 / d[h];
    const Double2 nc = n.x * cx[h] + n.y * cy[h] + n.z * cz[h];
    const Double2 term = AtanOverTOfSquare(c2[h] * (inv_d * inv_d)) * inv_d * nc;
    t[2 * h] = term[0];
    t[2 * h + 1] = term[1];
  }
}

}  // namespace

double UnclippedPointToPolygonFormFactor(const Vec3& x, const Vec3& n,
                                         std::span<const Vec3> polygon) {
  // The vertices relative to x, each once (vertex m is vertex 0 again), four edges at a time;
  // a last group of fewer repeats its last vertex (edges of length 0, terms not added). The
  // terms are added in edge order.
  const size_t m = polygon.size();
  const Vec3 first = polygon[0] - x;
  Vec3 v[5];
  v[0] = first;
  double sum = 0;
  for (size_t e = 0; e < m; e += 4) {
    const size_t edges = std::min<size_t>(4, m - e);
    for (size_t k = 1; k <= 4; ++k) {
      const size_t vertex = e + std::min(k, edges);
      v[k] = vertex == m ? first : polygon[vertex] - x;
    }
    double t[4];
    FourContourEdgeTerms(v, n, t);
    for (size_t k = 0; k < edges; ++k) sum += t[k];
    v[0] = v[4];
  }
  return FormFactorFromContourSum(sum);
}

double PointToPolygonFormFactor(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon) {
  bool all_front = true, any_front = false;
  for (const Vec3& p : polygon) {
    const double d = Dot(p - x, n);
    all_front = all_front && d >= 0;
    any_front = any_front || d > 0;
  }
  if (!any_front) return 0;
  if (all_front) return UnclippedPointToPolygonFormFactor(x, n, polygon);
  const std::vector<Vec3> clipped = ClipPolygonToHalfSpace(polygon, x, n);
  return clipped.size() < 3 ? 0 : UnclippedPointToPolygonFormFactor(x, n, clipped);
}

}  // namespace radflux
