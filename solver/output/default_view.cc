#include "solver/output/default_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

namespace radflux {
namespace {

constexpr int kGrid = 6;                // probe points per box axis
constexpr int kProbeRays = 64;          // rays per probe point
constexpr int kAzimuths = 16;           // horizontal rays from the chosen point
constexpr double kInsideLimit = 0.25;   // most rays that may escape or see a back face
constexpr double kLitShare = 0.5;       // fewest rays that must meet a lit patch (not the
                                        // dark inside of a closed solid or of a luminaire)
constexpr double kEyeHeight = 0.55;     // fraction of the floor-to-ceiling height
constexpr double kBackOff = 0.9;        // fraction of the way to the wall behind
constexpr double kSnapDegrees = 10;     // a long axis this close to a box axis is that axis
constexpr int kOpenAzimuths = 8;        // azimuths an open scene is tried from
constexpr int kOpenProbeWidth = 32;     // pixels across the pictures they are compared by
constexpr double kNearFraction = 1e-3;  // nearest corner's depth, fraction of the box diagonal
constexpr int kOpeningRays = 3;         // horizontal rays that escape through a missing side
                                        // (a window or a door lets fewer through)

struct Box {
  Vec3 lo, hi;
  Vec3 Centre() const { return (lo + hi) * 0.5; }
  Vec3 Extent() const { return hi - lo; }
};

Box Bounds(const PatchMesh& mesh) {
  Box box{mesh.positions.at(0), mesh.positions.at(0)};
  for (const Vec3& p : mesh.positions) {
    box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y), std::min(box.lo.z, p.z)};
    box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y), std::max(box.hi.z, p.z)};
  }
  return box;
}

Vec3 Axis(int i, double sign) {
  return {i == 0 ? sign : 0.0, i == 1 ? sign : 0.0, i == 2 ? sign : 0.0};
}

// Index of the box axis closest to direction d.
int NearestAxis(const Vec3& d) {
  int best = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(d[i]) > std::abs(d[best])) best = i;
  }
  return best;
}

// Unit direction i of n spread evenly over the sphere (a Fibonacci lattice).
Vec3 SphereDirection(int i, int n) {
  const double z = 1 - (2 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  const double phi = i * std::numbers::pi * (3 - std::sqrt(5.0));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

struct Cast {
  bool escaped = false;
  bool back = false;  // hit the back of a one-sided patch
  bool lit = false;   // hit the front of a patch with B > 0 in some band
  double distance = 0;
};

// The scene as the rule's rays see it.
struct Probe {
  const PatchMesh& mesh;
  const RayCaster& caster;
  std::span<const Rgb> radiosity;  // per patch

  Cast operator()(const Vec3& origin, const Vec3& unit) const {
    const Hit hit = caster.Intersect({origin, unit, 0, std::numeric_limits<double>::infinity()});
    if (hit.patch == kNoPatch || hit.patch >= mesh.size()) return {true, false, false, 0};
    const Patch& patch = mesh.patches[hit.patch];
    const bool back = Dot(unit, patch.normal) >= 0 && !patch.two_sided;
    return {false, back, !back && MaxComponent(radiosity[hit.patch]) > 0, hit.t};
  }
};

// Distance from p (inside the box) to the box's boundary along unit d.
double DistanceToBox(const Box& box, const Vec3& p, const Vec3& d) {
  double t = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (d[i] > 0) t = std::min(t, (box.hi[i] - p[i]) / d[i]);
    if (d[i] < 0) t = std::min(t, (box.lo[i] - p[i]) / d[i]);
  }
  return std::max(t, 0.0);
}

// The probe point with the largest mean free distance among those inside, if any.
std::optional<Vec3> LargestOpenVolume(const Probe& probe, const Box& box) {
  std::optional<Vec3> best;
  double best_distance = -1;
  const Vec3 e = box.Extent();
  for (int i = 0; i < kGrid * kGrid * kGrid; ++i) {
    const Vec3 f{(i % kGrid + 0.5) / kGrid, (i / kGrid % kGrid + 0.5) / kGrid,
                 (i / (kGrid * kGrid) + 0.5) / kGrid};
    const Vec3 p = box.lo + Vec3{e.x * f.x, e.y * f.y, e.z * f.z};
    int outside = 0, hits = 0, lit = 0;
    double sum = 0;
    for (int k = 0; k < kProbeRays; ++k) {
      const Cast c = probe(p, SphereDirection(k, kProbeRays));
      if (c.escaped || c.back) {
        ++outside;
      } else {
        ++hits, sum += c.distance, lit += c.lit;
      }
    }
    if (outside > kInsideLimit * kProbeRays || lit < kLitShare * kProbeRays) continue;
    if (sum / hits > best_distance) best_distance = sum / hits, best = p;
  }
  return best;
}

// Looking at the box's centre along box axis `forward` from outside, the box's cross-section
// filling the picture (no background shows around an opening).
Camera Filled(const Box& box, Camera camera, const Vec3& forward) {
  const int f = NearestAxis(forward), u = NearestAxis(camera.up), side = 3 - f - u;
  const Vec3 e = box.Extent();
  const double half_height = e[u] / 2, half_width = e[side] / 2 * camera.height / camera.width;
  const double half = std::min(half_height, half_width);
  const double distance = half / std::tan(camera.vertical_fov_degrees * std::numbers::pi / 360);
  camera.look_at = box.Centre();
  camera.position = camera.look_at - forward * (e[f] / 2 + distance);
  return camera;
}

// Distance from the box's centre, back along unit `forward`, at which every corner of the
// box is in the picture (and in front of the eye).
double FittingDistance(const Box& box, const Camera& camera, const Vec3& forward) {
  const Vec3 right = Normalize(Cross(forward, camera.up)), up = Cross(right, forward);
  const double tan_v = std::tan(camera.vertical_fov_degrees * std::numbers::pi / 360);
  const double tan_h = tan_v * camera.width / camera.height;
  double distance = 0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 r = Vec3{i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                        i & 4 ? box.hi.z : box.lo.z} -
                   box.Centre();
    const double fit = std::max(std::abs(Dot(r, right)) / tan_h, std::abs(Dot(r, up)) / tan_v);
    distance =
        std::max(distance, std::max(fit, kNearFraction * Length(box.Extent())) - Dot(r, forward));
  }
  return distance;
}

// Pixels of a kOpenProbeWidth-wide picture of `camera` that see a lit patch.
int LitPixels(const Probe& probe, Camera camera) {
  camera.height = std::max(1, kOpenProbeWidth * camera.height / camera.width);
  camera.width = kOpenProbeWidth;
  const PinholeProjection projection(camera);
  int lit = 0;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = projection.RayThrough(x + 0.5, y + 0.5);
      lit += probe(ray.origin, ray.direction).lit;
    }
  }
  return lit;
}

// An open scene seen from outside (see the header's rule): of the views of the box's centre
// from 8 azimuths around up at elevations +30, 0 and -30 degrees, each with the whole box in
// the picture, the first with the most lit pixels.
Camera OpenView(const Probe& probe, const Box& box, Camera camera) {
  const Vec3 up = Normalize(camera.up);
  const Vec3 axis = NearestAxis(up) == 2 ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
  const Vec3 h1 = Normalize(axis - up * Dot(axis, up)), h2 = Cross(up, h1);
  Camera best = camera;
  int best_lit = -1;
  for (const double elevation : {30.0, 0.0, -30.0}) {
    const double e = elevation * std::numbers::pi / 180;
    for (int k = 0; k < kOpenAzimuths; ++k) {
      const double a = 2 * std::numbers::pi * k / kOpenAzimuths;
      const Vec3 forward = (h1 * std::cos(a) + h2 * std::sin(a)) * std::cos(e) - up * std::sin(e);
      camera.look_at = box.Centre();
      camera.position = camera.look_at - forward * FittingDistance(box, camera, forward);
      const int lit = LitPixels(probe, camera);
      if (lit > best_lit) best_lit = lit, best = camera;
    }
  }
  return best;
}

// The view from inside, around open point p (see the header's rule).
Camera InteriorView(const Probe& probe, const Box& box, Camera camera, const Vec3& p) {
  const Vec3 up = Normalize(camera.up);
  auto free = [&](const Vec3& from, const Vec3& d) {
    const Cast c = probe(from, d);
    return c.escaped ? DistanceToBox(box, from, d) : c.distance;
  };
  const double below = free(p, -up), above = free(p, up);
  const Vec3 eye = p + up * (kEyeHeight * (below + above) - below);
  const int up_axis = NearestAxis(up);
  const Vec3 h1 = Normalize(Cross(up, Axis((up_axis + 2) % 3, 1)));
  const Vec3 h2 = Cross(up, h1);
  Vec3 dirs[kAzimuths], opening;
  double distance[kAzimuths];
  int escaped = 0;
  for (int k = 0; k < kAzimuths; ++k) {
    const double angle = 2 * std::numbers::pi * k / kAzimuths;
    dirs[k] = h1 * std::cos(angle) + h2 * std::sin(angle);
    const Cast c = probe(eye, dirs[k]);
    distance[k] = c.escaped ? DistanceToBox(box, eye, dirs[k]) : c.distance;
    if (c.escaped) opening += dirs[k], ++escaped;
  }
  if (escaped >= kOpeningRays) {
    Vec3 in = -opening;
    in = in - up * Dot(in, up);
    const int axis = NearestAxis(in);
    return Filled(box, camera, Axis(axis, in[axis] >= 0 ? 1 : -1));
  }
  // The principal axis of the horizontal hit points around the eye: the long axis.
  double mx = 0, my = 0, cxx = 0, cxy = 0, cyy = 0;
  for (int k = 0; k < kAzimuths; ++k) {
    mx += distance[k] * Dot(dirs[k], h1) / kAzimuths,
        my += distance[k] * Dot(dirs[k], h2) / kAzimuths;
  }
  for (int k = 0; k < kAzimuths; ++k) {
    const double x = distance[k] * Dot(dirs[k], h1) - mx, y = distance[k] * Dot(dirs[k], h2) - my;
    cxx += x * x, cxy += x * y, cyy += y * y;
  }
  const double angle = 0.5 * std::atan2(2 * cxy, cxx - cyy);
  Vec3 ahead = h1 * std::cos(angle) + h2 * std::sin(angle);
  const int axis = NearestAxis(ahead);  // within 10 degrees of a box axis: that axis
  if (std::abs(ahead[axis]) > std::cos(kSnapDegrees * std::numbers::pi / 180)) {
    ahead = Axis(axis, ahead[axis] > 0 ? 1 : -1);
  }
  double front = free(eye, ahead), back = free(eye, -ahead);
  if (front < back) std::swap(front, back), ahead = -ahead;
  camera.position = eye - ahead * (kBackOff * back);
  camera.look_at = camera.position + ahead;
  return camera;
}

}  // namespace

Vec3 SceneUpAxis(const PatchMesh& mesh) {
  double facing_y = 0, facing_z = 0;  // area of patches facing along the axis (either way)
  for (const Patch& patch : mesh.patches) {
    if (std::abs(patch.normal.y) > 0.9) facing_y += patch.area;
    if (std::abs(patch.normal.z) > 0.9) facing_z += patch.area;
  }
  return facing_z > facing_y ? Vec3{0, 0, 1} : Vec3{0, 1, 0};
}

Camera DefaultCamera(const PatchMesh& mesh, const RayCaster& caster, std::span<const Rgb> radiosity,
                     const Camera& camera, const Vec3& up) {
  const Probe probe{mesh, caster, radiosity};
  Camera view = camera;
  view.up = Length(up) > 0 ? up : SceneUpAxis(mesh);
  const Box box = Bounds(mesh);
  const std::optional<Vec3> open = LargestOpenVolume(probe, box);
  if (open) {
    const Camera inside = InteriorView(probe, box, view, *open);
    if (ValidateCamera(inside).ok()) return inside;
  }
  return OpenView(probe, box, view);
}

}  // namespace radflux
