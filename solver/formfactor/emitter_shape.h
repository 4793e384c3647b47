// EmitterShape: one emitter patch as a light source: its polygon, power and the
// solid-angle sampler that fits it (Urena et al.'s for rectangles, Arvo's for triangles and
// for the two halves of other quads).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "solver/core/sampling.h"
#include "solver/core/spherical_sampling.h"
#include "solver/mesh/patch_mesh.h"

namespace radflux {

struct EmitterShape {
  uint32_t patch = 0;          // the unknown (row and column) it is: light sampling's column
  std::array<Vec3, 4> corner;  // ccw; corner[3] == corner[2] for a triangle
  uint32_t corners = 0;        // 3 or 4
  Vec3 normal;                 // unit, the emitting (front) side
  double area = 0;             // scene units^2
  double opacity = 1;          // Patch::opacity: a ray meets it (and its light) with this
  double power = 0;            // E A opacity summed over bands, W (importance only)
  bool rectangle = false;      // a quad with parallel, orthogonal sides
  Vec3 centre;                 // the corners' mean
  double radius = 0;           // the corners' greatest distance from it
};

// Sets shape.centre and shape.radius from its corners.
void SetEmitterBounds(EmitterShape& shape);

// The shape of patch p of `mesh` emitting `exitance` (W/m^2, summed over bands).
EmitterShape MakeEmitterShape(const PatchMesh& mesh, uint32_t p, double exitance);

// Lambert's exact form factor from the differential area at x (unit normal n) to the
// emitter (the part in front of x); 0 when x is not in front of the emitting side.
double EmitterFormFactor(const EmitterShape& shape, const Vec3& x, const Vec3& n);

// Where the ray from x along direction w meets the emitter, into `point`; false when it
// misses it (or meets its back side).
bool EmitterHit(const EmitterShape& shape, const Vec3& x, const Vec3& w, Vec3& point);

// The emitter's unoccluded contribution at receiver point x with unit normal n, up to a
// constant: pi E F(x -> shape) = power / area * pi * F, with F Lambert's exact point-to-polygon
// form factor of the part in front of x; 0 when x is not in front of the emitting side.
double EmitterImportance(const EmitterShape& shape, const Vec3& x, const Vec3& n);
// The same from that form factor F, already computed (EmitterFormFactor(shape, x, n)).
double EmitterImportance(const EmitterShape& shape, double form_factor);

// EmitterImportance's estimate for a polygon seen from afar (ReachOf's far): `power` times
// the integrand cos_x cos_y / r^2 averaged over its corners (`normal` its emitting side), the
// mean of a bilinear fit of the integrand across it, as sampling a far emitter by area
// assumes: no trigonometry, about a fifth of the exact form factor's cost, and within a small
// factor of it from kFarRadii on (tested). Zero exactly where the exact contribution is: x not
// in front of the polygon's plane, or no corner strictly in front of x's tangent plane (a
// convex polygon lies on the side of a plane its corners lie on).
double FarEmitterImportance(std::span<const Vec3> corners, const Vec3& normal, double power,
                            const Vec3& x, const Vec3& n);

// Where an emitter lies from receiver point x: far when x is at least kFarRadii of its radii
// (its corners' greatest distance from their mean) from its centre; and then an upper bound
// on its form factor from x (every point of it at least max(h, d - radius) away, h x's
// height over its plane, d the distance to its centre; cos_y = h / r, cos_x <= 1), else
// infinity.
inline constexpr double kFarRadii = 4;
struct EmitterReach {
  bool far = false;
  double max_form_factor = INFINITY;
};
EmitterReach ReachOf(const EmitterShape& shape, const Vec3& x);

// A point on the emitter seen from receiver point x with unit normal n, and its pdf per
// steradian (0 when the emitter subtends no solid angle at x). Near the emitter: the
// solid-angle map of the shape (uniform, pdf 1 / solid angle) composed with a bilinear warp of
// u whose corner weights are the receiver's cosines towards the corners (at least 0.01).
// Far from it (ReachOf): a point uniform in area (a rectangle's by its sides, a triangle's by
// SampleUniformTriangle, another quad's in the triangle (0, 1, 2) or (0, 2, 3) chosen by u.x
// with their shares of the area) composed with a bilinear
// warp whose corner weights are the integrand cos_x cos_y / r^2 at the corners (at least 0.01
// of their largest), its pdf converted to solid angle (r^2 / cos_y): no trigonometry, and
// across a far emitter the integrand is nearly bilinear. Either way the density roughly
// follows cos(theta_x) and an estimate of cos / pdf varies little.
struct EmitterSample {
  Vec3 point;
  double pdf = 0;
};
EmitterSample SampleEmitterSolidAngle(const EmitterShape& shape, const Vec3& x, const Vec3& n,
                                      Point2 u);

// SampleEmitterSolidAngle for many u at one emitter and receiver point: what does not
// depend on u (the corners' weights, a rectangle's set-up, a quad's halves' shares) is
// computed once, and each sample is SampleEmitterSolidAngle's, bit for bit. Keeps a
// reference to `shape`.
class EmitterPointSampler {
 public:
  EmitterPointSampler(const EmitterShape& shape, const Vec3& x, const Vec3& n);
  EmitterSample operator()(Point2 u) const;

 private:
  // The far emitter's sample (by area).
  EmitterSample ByArea(Point2 u) const;

  const EmitterShape& shape_;
  Vec3 x_;
  bool far_ = false;
  std::array<double, 4> weight_{};                      // the warp's weight of each corner
  std::optional<SphericalRectangleSampler> rectangle_;  // a near rectangle's set-up
  double share_ = 1;  // a quad's first half's share of its solid angle, or area (< 0: none)
};

}  // namespace radflux
