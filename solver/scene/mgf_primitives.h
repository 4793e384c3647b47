// MGF's curved and compound surfaces as polygons: sph, cyl, cone, ring, torus, prism, and
// faces with holes (fh). Everything is built in the coordinates of its vertices; the loader
// applies the transform afterwards.
//
// Tessellation with n = ImportOptions::curve_segments (n >= 3):
// - cone / cyl: n quads around (triangles at a zero radius).
// - ring: n quads (n triangles for a disk, inner radius 0).
// - sph: n segments around the axis and ceil(n/2) latitude bands pole to pole (triangles at
//   the poles): about n^2/2 faces.
// - torus: n segments around its axis times n segments around the tube: n^2 quads.
// Every vertex lies on the true surface, so each facet is a chord (inscribed): areas come out
// low by a relative error below (pi/n)^2 (e.g. 3.9% at n = 16, 0.24% at n = 64); for the cone,
// cylinder and ring exactly by the factor sin(pi/n)/(pi/n) (times cos(pi/n) for the ring and
// disk, whose facets are chords of both circles).
// Orientation: outward (away from the axis, centre or tube) for positive radii, inward for
// negative ones; a ring faces along its vertex normal; a prism is a closed solid facing out.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/vec3.h"

namespace radflux {

// Points and the faces over them (indices into points, counter-clockwise seen from the front).
struct MgfMesh {
  std::vector<Vec3> points;
  std::vector<std::vector<uint32_t>> faces;
};

// Errors below carry no location; the loader prefixes file:line.

// sph: sphere of `radius` (negative: facing inward). Error for radius 0.
absl::StatusOr<MgfMesh> TessellateSphere(const Vec3& centre, double radius, int segments);

// cone (cyl when r_a == r_b): open truncated cone from `a` (radius r_a) to `b` (radius r_b).
// Radii of one sign (negative: inward), not both 0; a != b.
absl::StatusOr<MgfMesh> TessellateCone(const Vec3& a, double r_a, const Vec3& b, double r_b,
                                       int segments);

// ring: annulus between r_in >= 0 and r_out > r_in around `centre`, facing along `normal`
// (the vertex's `n`, must be non-zero).
absl::StatusOr<MgfMesh> TessellateRing(const Vec3& centre, const Vec3& normal, double r_in,
                                       double r_out, int segments);

// torus: the tube between radii r_in and r_out from the axis through `centre` along `normal`
// (tube radius (r_out - r_in) / 2). Both radii negative (with r_out < r_in): facing inward.
absl::StatusOr<MgfMesh> TessellateTorus(const Vec3& centre, const Vec3& normal, double r_in,
                                        double r_out, int segments);

// prism: the polygon `base` extruded by `length` against its normal (right-hand rule), as a
// closed solid: the base, the moved copy reversed and one quad per edge, facing out (for a
// negative length the copy lies in front of the base and, as in MGF's parser, every face
// faces in). Error for a base without area or length 0.
absl::StatusOr<MgfMesh> ExtrudePrism(const std::vector<Vec3>& base, double length);

// fh: one contour visiting `outer` and every hole, each hole joined by a bridge edge that is
// walked both ways (so the contour touches itself along the bridge; the import rules then
// triangulate it). Returns indices into the concatenation outer ++ holes[0] ++ holes[1] ...;
// holes wound like the outer contour are reversed. Error when the outer contour has no area
// or a hole cannot be joined without crossing an edge.
absl::StatusOr<std::vector<uint32_t>> BridgeHoles(const std::vector<Vec3>& outer,
                                                  const std::vector<std::vector<Vec3>>& holes);

}  // namespace radflux
