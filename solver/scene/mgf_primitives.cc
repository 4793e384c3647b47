#include "solver/scene/mgf_primitives.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "solver/scene/scene.h"

namespace radflux {
namespace {

constexpr double kPi = std::numbers::pi;

// A point of a profile curve: distance from the axis and height along it.
struct ProfilePoint {
  double rho = 0, z = 0;
};

// The surface swept by the polyline `profile` turning about the axis through `origin` along
// unit `axis`, `segments` steps around. Band k joins profile[k] and profile[k + 1] (and the
// last to the first when `closed`); each face is wound so that its normal agrees with
// outward[k], a (rho, z) direction. Points on the axis (rho 0) are shared, giving triangles.
MgfMesh Revolve(const Vec3& origin, const Vec3& axis, const std::vector<ProfilePoint>& profile,
                const std::vector<ProfilePoint>& outward, int segments, bool closed) {
  const Frame frame = Frame::FromNormal(axis);
  auto radial = [&](double angle) { return frame.s * std::cos(angle) + frame.t * std::sin(angle); };
  MgfMesh mesh;
  std::vector<uint32_t> first;  // index of each profile point's first ring point
  for (const ProfilePoint& p : profile) {
    first.push_back(static_cast<uint32_t>(mesh.points.size()));
    const int count = p.rho == 0 ? 1 : segments;
    for (int i = 0; i < count; ++i) {
      mesh.points.push_back(origin + axis * p.z + radial(2 * kPi * i / segments) * p.rho);
    }
  }
  auto at = [&](size_t k, int i) {
    return profile[k].rho == 0 ? first[k] : first[k] + static_cast<uint32_t>(i % segments);
  };
  const size_t bands = closed ? profile.size() : profile.size() - 1;
  for (size_t k = 0; k < bands; ++k) {
    const size_t k1 = (k + 1) % profile.size();
    for (int i = 0; i < segments; ++i) {
      std::vector<uint32_t> face;
      for (uint32_t v : {at(k, i), at(k, i + 1), at(k1, i + 1), at(k1, i)}) {
        if (std::find(face.begin(), face.end(), v) == face.end()) face.push_back(v);
      }
      if (face.size() < 3) continue;
      std::vector<Vec3> polygon;
      for (uint32_t v : face) polygon.push_back(mesh.points[v]);
      const Vec3 expected =
          radial(2 * kPi * (i + 0.5) / segments) * outward[k].rho + axis * outward[k].z;
      if (Dot(PolygonNewellNormal(polygon), expected) < 0) std::reverse(face.begin(), face.end());
      mesh.faces.push_back(std::move(face));
    }
  }
  return mesh;
}

absl::Status CheckSegments(int segments) {
  if (segments < 3) return absl::InvalidArgumentError("curve segments must be at least 3");
  return absl::OkStatus();
}

// The unit vector along `v`, or an error naming `what` when v is zero.
absl::StatusOr<Vec3> UnitAxis(const Vec3& v, const char* what) {
  const double length = Length(v);
  if (!(length > 0) || !std::isfinite(length)) {
    return absl::InvalidArgumentError(absl::StrCat(what, " is zero"));
  }
  return v / length;
}

}  // namespace

absl::StatusOr<MgfMesh> TessellateSphere(const Vec3& centre, double radius, int segments) {
  if (absl::Status s = CheckSegments(segments); !s.ok()) return s;
  if (radius == 0) return absl::InvalidArgumentError("sph radius is 0");
  const int bands = std::max(2, (segments + 1) / 2);
  const double r = std::abs(radius), sign = radius > 0 ? 1 : -1;
  std::vector<ProfilePoint> profile, outward;
  for (int k = 0; k <= bands; ++k) {
    const double polar = kPi * k / bands;
    const bool pole = k == 0 || k == bands;
    profile.push_back({pole ? 0.0 : r * std::sin(polar), r * std::cos(polar)});
    const double mid = kPi * (k + 0.5) / bands;
    outward.push_back({sign * std::sin(mid), sign * std::cos(mid)});
  }
  return Revolve(centre, {0, 0, 1}, profile, outward, segments, false);
}

absl::StatusOr<MgfMesh> TessellateCone(const Vec3& a, double r_a, const Vec3& b, double r_b,
                                       int segments) {
  if (absl::Status s = CheckSegments(segments); !s.ok()) return s;
  if (r_a == 0 && r_b == 0) return absl::InvalidArgumentError("cone radii are both 0");
  if ((r_a < 0 && r_b > 0) || (r_a > 0 && r_b < 0)) {
    return absl::InvalidArgumentError("cone radii have opposite signs");
  }
  absl::StatusOr<Vec3> axis = UnitAxis(b - a, "cone axis (end vertices coincide)");
  if (!axis.ok()) return axis.status();
  const double height = Length(b - a);
  const double sign = r_a + r_b > 0 ? 1 : -1;
  const double ra = std::abs(r_a), rb = std::abs(r_b);
  const ProfilePoint normal{sign * height, -sign * (rb - ra)};
  return Revolve(a, *axis, {{ra, 0}, {rb, height}}, {normal}, segments, false);
}

absl::StatusOr<MgfMesh> TessellateRing(const Vec3& centre, const Vec3& normal, double r_in,
                                       double r_out, int segments) {
  if (absl::Status s = CheckSegments(segments); !s.ok()) return s;
  absl::StatusOr<Vec3> axis = UnitAxis(normal, "ring vertex normal");
  if (!axis.ok()) return axis.status();
  if (r_in < 0 || !(r_out > r_in)) {
    return absl::InvalidArgumentError("ring radii must satisfy 0 <= inner < outer");
  }
  return Revolve(centre, *axis, {{r_in, 0}, {r_out, 0}}, {{0, 1}}, segments, false);
}

absl::StatusOr<MgfMesh> TessellateTorus(const Vec3& centre, const Vec3& normal, double r_in,
                                        double r_out, int segments) {
  if (absl::Status s = CheckSegments(segments); !s.ok()) return s;
  absl::StatusOr<Vec3> axis = UnitAxis(normal, "torus vertex normal");
  if (!axis.ok()) return axis.status();
  const double sign = r_in != 0 ? (r_in > 0 ? 1 : -1) : (r_out > 0 ? 1 : -1);
  if (!(sign * (r_out - r_in) > 0)) {
    return absl::InvalidArgumentError(
        "torus radii must satisfy 0 <= inner < outer (or both negated)");
  }
  const double major = std::abs(r_in + r_out) / 2, minor = std::abs(r_out - r_in) / 2;
  std::vector<ProfilePoint> profile, outward;
  for (int j = 0; j < segments; ++j) {
    const double phi = -kPi / 2 + 2 * kPi * j / segments;
    const double mid = phi + kPi / segments;
    const double rho = major + minor * std::cos(phi);
    profile.push_back({std::abs(rho) < 1e-12 * major ? 0.0 : rho, minor * std::sin(phi)});
    outward.push_back({sign * std::cos(mid), sign * std::sin(mid)});
  }
  return Revolve(centre, *axis, profile, outward, segments, true);
}

absl::StatusOr<MgfMesh> ExtrudePrism(const std::vector<Vec3>& base, double length) {
  if (base.size() < 3) return absl::InvalidArgumentError("prism needs at least 3 vertices");
  if (length == 0) return absl::InvalidArgumentError("prism length is 0");
  absl::StatusOr<Vec3> normal = UnitAxis(PolygonNewellNormal(base), "prism base area");
  if (!normal.ok()) return normal.status();
  const uint32_t n = static_cast<uint32_t>(base.size());
  MgfMesh mesh;
  mesh.points = base;
  for (const Vec3& p : base) mesh.points.push_back(p - *normal * length);
  std::vector<uint32_t> bottom, top;
  for (uint32_t i = 0; i < n; ++i) {
    bottom.push_back(i);
    top.push_back(2 * n - 1 - i);
    const uint32_t prev = (i + n - 1) % n;
    mesh.faces.push_back({n + i, i, prev, n + prev});
  }
  mesh.faces.push_back(std::move(bottom));
  mesh.faces.push_back(std::move(top));
  return mesh;
}

namespace {

// Coordinates of `p` in the plane that drops the axis where `normal` is largest.
std::pair<double, double> Project(const Vec3& p, const Vec3& normal) {
  const double ax = std::abs(normal.x), ay = std::abs(normal.y), az = std::abs(normal.z);
  if (ax >= ay && ax >= az) return {p.y, p.z};
  if (ay >= az) return {p.z, p.x};
  return {p.x, p.y};
}

using Point2 = std::pair<double, double>;

double Orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b.first - a.first) * (c.second - a.second) - (b.second - a.second) * (c.first - a.first);
}

// Whether segments pq and rs cross or touch (collinear overlap included).
bool SegmentsMeet(const Point2& p, const Point2& q, const Point2& r, const Point2& s) {
  const double d1 = Orient(r, s, p), d2 = Orient(r, s, q), d3 = Orient(p, q, r),
               d4 = Orient(p, q, s);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
  auto on = [](const Point2& a, const Point2& b, const Point2& c, double d) {
    return d == 0 && std::min(a.first, b.first) <= c.first &&
           c.first <= std::max(a.first, b.first) && std::min(a.second, b.second) <= c.second &&
           c.second <= std::max(a.second, b.second);
  };
  return on(r, s, p, d1) || on(r, s, q, d2) || on(p, q, r, d3) || on(p, q, s, d4);
}

// Whether the bridge a-b (point indices) meets any edge of the closed loops, other than at a
// shared end point.
bool BridgeBlocked(uint32_t a, uint32_t b, const std::vector<std::vector<uint32_t>>& loops,
                   const std::vector<Point2>& pts) {
  for (const std::vector<uint32_t>& loop : loops) {
    for (size_t e = 0; e < loop.size(); ++e) {
      const uint32_t c = loop[e], d = loop[(e + 1) % loop.size()];
      if (c == a || c == b || d == a || d == b) continue;
      if (SegmentsMeet(pts[a], pts[b], pts[c], pts[d])) return true;
    }
  }
  return false;
}

}  // namespace

absl::StatusOr<std::vector<uint32_t>> BridgeHoles(const std::vector<Vec3>& outer,
                                                  const std::vector<std::vector<Vec3>>& holes) {
  absl::StatusOr<Vec3> normal = UnitAxis(PolygonNewellNormal(outer), "fh outer contour area");
  if (!normal.ok()) return normal.status();
  std::vector<Vec3> all = outer;
  std::vector<std::vector<uint32_t>> loops(1);  // loops[0]: the contour built so far
  for (uint32_t i = 0; i < outer.size(); ++i) loops[0].push_back(i);
  for (const std::vector<Vec3>& hole : holes) {
    std::vector<uint32_t> loop;
    for (const Vec3& p : hole) {
      loop.push_back(static_cast<uint32_t>(all.size()));
      all.push_back(p);
    }
    if (Dot(PolygonNewellNormal(hole), *normal) > 0) std::reverse(loop.begin(), loop.end());
    loops.push_back(std::move(loop));
  }
  std::vector<Point2> pts;
  for (const Vec3& p : all) pts.push_back(Project(p, *normal));
  while (loops.size() > 1) {
    const std::vector<uint32_t> hole = loops[1];
    // Candidate bridges, shortest first.
    std::vector<std::pair<double, std::pair<size_t, size_t>>> candidates;
    for (size_t i = 0; i < loops[0].size(); ++i) {
      for (size_t j = 0; j < hole.size(); ++j) {
        const Vec3 d = all[loops[0][i]] - all[hole[j]];
        candidates.push_back({Dot(d, d), {i, j}});
      }
    }
    std::sort(candidates.begin(), candidates.end());
    const auto found = std::find_if(candidates.begin(), candidates.end(), [&](const auto& c) {
      return !BridgeBlocked(loops[0][c.second.first], hole[c.second.second], loops, pts);
    });
    if (found == candidates.end()) {
      return absl::InvalidArgumentError("fh hole cannot be joined to the outer contour");
    }
    const auto [i, j] = found->second;
    std::vector<uint32_t> merged(loops[0].begin(), loops[0].begin() + static_cast<long>(i) + 1);
    for (size_t k = 0; k <= hole.size(); ++k) merged.push_back(hole[(j + k) % hole.size()]);
    merged.insert(merged.end(), loops[0].begin() + static_cast<long>(i), loops[0].end());
    loops[0] = std::move(merged);
    loops.erase(loops.begin() + 1);
  }
  return loops[0];
}

}  // namespace radflux
