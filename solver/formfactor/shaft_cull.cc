#include "solver/formfactor/shaft_cull.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/core/parallel.h"

namespace radflux {
namespace {

constexpr double kRelativeTolerance = 1e-9;

// The extent [lo, hi] of the points of `s` along `axis`, merged into lo and hi.
void Extend(const SurfaceShape& s, const Vec3& axis, double& lo, double& hi) {
  for (const Vec3& p : s.polygon) {
    const double v = Dot(p, axis);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
}

Vec3 Abs(const Vec3& v) { return {std::abs(v.x), std::abs(v.y), std::abs(v.z)}; }

// Whether the box [lo, hi] lies in front of s's plane beyond the narrowest coplanar band s
// can have with any surface (2 s.flatness + kCoplanarRelative s.diameter), with room for the
// rounding of the per-vertex tests (kRelativeTolerance of the box's scale): then no vertex in
// the box is behind s as PartlyBehind counts it, and s blocks nothing. Its lowest point on
// the normal is the box corner taking lo where the normal is positive, hi elsewhere.
bool BoxInFront(const SurfaceShape& s, const Vec3& lo, const Vec3& hi) {
  double lowest = 0, scale = 0;
  for (int c = 0; c < 3; ++c) {
    lowest += ((s.normal[c] >= 0 ? lo[c] : hi[c]) - s.centroid[c]) * s.normal[c];
    scale += std::abs(lo[c]) + std::abs(hi[c]) + std::abs(s.centroid[c]);
  }
  const double band = 2 * s.flatness + kCoplanarRelative * s.diameter;
  return lowest >= -band + kRelativeTolerance * scale;
}

}  // namespace

std::vector<uint32_t> PotentialBlockers(const std::vector<SurfaceShape>& shapes) {
  std::vector<uint8_t> blocks(shapes.size(), 0);
  if (shapes.empty()) return {};
  Vec3 lo = shapes[0].lo, hi = shapes[0].hi;
  for (const SurfaceShape& s : shapes) {
    lo = {std::min(lo.x, s.lo.x), std::min(lo.y, s.lo.y), std::min(lo.z, s.lo.z)};
    hi = {std::max(hi.x, s.hi.x), std::max(hi.y, s.hi.y), std::max(hi.z, s.hi.z)};
  }
  ParallelFor(static_cast<int64_t>(shapes.size()), 256, 0, [&](int64_t begin, int64_t end) {
    for (int64_t k = begin; k < end; ++k) {
      const SurfaceShape& s = shapes[k];
      if (BoxInFront(s, lo, hi)) continue;  // the scene's box in front: nothing behind
      for (const SurfaceShape& other : shapes) {
        if (PartlyBehind(s, other)) {
          blocks[k] = 1;
          break;
        }
      }
    }
  });
  std::vector<uint32_t> out;
  for (uint32_t k = 0; k < shapes.size(); ++k) {
    if (blocks[k]) out.push_back(k);
  }
  return out;
}

bool MayBlockPair(const SurfaceShape& i, const SurfaceShape& j, const SurfaceShape& k) {
  return PartlyInFront(i, k) && PartlyInFront(j, k);
}

Shaft::Shaft(const SurfaceShape& i, const SurfaceShape& j, double margin)
    : i_(i), j_(j), d_(j.centroid - i.centroid), margin_(margin) {
  const Vec3 units[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 3; ++a) {
    axis_[a] = units[a];
    abs_axis_[a] = units[a];
    lo_[a] = std::min(i.lo[a], j.lo[a]) - margin;
    hi_[a] = std::max(i.hi[a], j.hi[a]) + margin;
  }
}

void Shaft::Complete() const {
  const Vec3 units[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 3; ++a) axis_[5 + a] = Cross(d_, units[a]);
  axis_[3] = i_.normal;
  axis_[4] = j_.normal;
  for (int a = 3; a < kAxes; ++a) {
    lo_[a] = std::numeric_limits<double>::infinity();
    hi_[a] = -lo_[a];
    Extend(i_, axis_[a], lo_[a], hi_[a]);
    Extend(j_, axis_[a], lo_[a], hi_[a]);
    abs_axis_[a] = Abs(axis_[a]);
    const double m = margin_ * Length(axis_[a]);
    lo_[a] -= m;
    hi_[a] += m;
  }
  complete_ = true;
}

bool Shaft::MayMeetBox(const Vec3& center, const Vec3& half) const {
  for (int a = 0; a < 3; ++a) {
    if (center[a] + half[a] < lo_[a] || center[a] - half[a] > hi_[a]) return false;
  }
  if (!complete_) Complete();
  for (int a = 3; a < kAxes; ++a) {
    const double c = Dot(center, axis_[a]), r = Dot(half, abs_axis_[a]);
    if (c + r < lo_[a] || c - r > hi_[a]) return false;
  }
  return true;
}

// Whether the projections of the shaft (i and j) and of k on `axis` are disjoint.
bool Shaft::Separates(const Vec3& axis, const SurfaceShape& k) const {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  Extend(i_, axis, lo, hi);
  Extend(j_, axis, lo, hi);
  double klo = std::numeric_limits<double>::infinity(), khi = -klo;
  Extend(k, axis, klo, khi);
  const double m = margin_ * Length(axis);
  return khi < lo - m || klo > hi + m;
}

bool Shaft::MayHold(const SurfaceShape& k) const {
  for (int a = 0; a < 3; ++a) {  // the coordinate axes: bounding boxes
    if (k.hi[a] < lo_[a] || k.lo[a] > hi_[a]) return false;
  }
  if (!complete_) Complete();
  for (int a = 3; a < kAxes; ++a) {  // the normals of i and j, d x axes: k's polygon
    double klo = std::numeric_limits<double>::infinity(), khi = -klo;
    Extend(k, axis_[a], klo, khi);
    if (khi < lo_[a] || klo > hi_[a]) return false;
  }
  if (!MayBlockPair(i_, j_, k)) return false;
  if (Separates(k.normal, k)) return false;
  for (size_t e = 0; e < k.polygon.size(); ++e) {
    const Vec3 axis = Cross(d_, k.polygon[(e + 1) % k.polygon.size()] - k.polygon[e]);
    if (Dot(axis, axis) > 0 && Separates(axis, k)) return false;
  }
  return true;
}

bool ShaftMayHold(const SurfaceShape& i, const SurfaceShape& j, const SurfaceShape& k) {
  if (&k == &i || &k == &j) return false;
  return Shaft(i, j, kRelativeTolerance * (i.diameter + j.diameter + k.diameter)).MayHold(k);
}

}  // namespace radflux
