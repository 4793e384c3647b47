#include "solver/formfactor/shaft_visibility.h"

#include <algorithm>
#include <vector>

#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

constexpr size_t kMaxSamplePoints = 8;

// Sample points on the part of s in front of `other`'s plane (the part that can see it):
// halfway between that part's centre (s's centroid, or the clipped part's vertex mean) and each of its first kMaxSamplePoints vertices.
// A pair whose surfaces both face each other whole (most) takes s's own polygon, unclipped.
size_t SamplePoints(const SurfaceShape& s, const SurfaceShape& other, Vec3 (&out)[kMaxSamplePoints]) {
  bool whole = true;
  for (const Vec3& p : s.polygon) whole = whole && Dot(p - other.centroid, other.normal) >= 0;
  std::vector<Vec3> clipped;
  if (!whole) clipped = ClipPolygonToHalfSpace(s.polygon, other.centroid, other.normal);
  const std::vector<Vec3>& part = whole || clipped.size() < 3 ? s.polygon : clipped;
  Vec3 center = s.centroid;
  if (&part == &clipped) {
    center = Vec3{};
    for (const Vec3& p : part) center += p;
    center = center / static_cast<double>(part.size());
  }
  const size_t n = std::min(part.size(), kMaxSamplePoints);
  for (size_t k = 0; k < n; ++k) out[k] = (center + part[k]) * 0.5;
  return n;
}

}  // namespace

bool SegmentHitsSurface(const Vec3& a, const Vec3& b, const SurfaceShape& k) {
  const double da = Dot(a - k.centroid, k.normal), db = Dot(b - k.centroid, k.normal);
  if ((da > 0) == (db > 0) || da == 0 || db == 0) return false;  // not crossing its plane
  const Vec3 q = a + (b - a) * (da / (da - db));
  const size_t n = k.polygon.size();
  for (size_t e = 0; e < n; ++e) {
    const Vec3& p = k.polygon[e];
    if (Dot(Cross(k.polygon[(e + 1) % n] - p, q - p), k.normal) < 0) return false;
  }
  return true;
}

double VisibleFraction(const SurfaceShape& i, const SurfaceShape& j, SegmentTest blocked,
                       uint64_t& segments) {
  Vec3 pi[kMaxSamplePoints], pj[kMaxSamplePoints];
  const size_t ni = SamplePoints(i, j, pi), nj = SamplePoints(j, i, pj);
  double seen = 0, total = 0;
  for (size_t a = 0; a < ni; ++a) {
    for (size_t b = 0; b < nj; ++b) {
      const Vec3 d = pj[b] - pi[a];
      const double r2 = Dot(d, d);
      const double w = r2 > 0 ? std::max(0.0, Dot(d, i.normal)) *
                                    std::max(0.0, -Dot(d, j.normal)) / (r2 * r2)
                              : 0;
      if (w <= 0) continue;
      ++segments;
      total += w;
      if (!blocked(pi[a], pj[b])) seen += w;
    }
  }
  return total > 0 ? seen / total : 1.0;
}

}  // namespace radflux
