// How a scene file becomes a Scene: the import rules a user can set (issue 19). One struct
// for every format (OBJ, glTF, MGF, STL, View3D), filled from the same CLI flags by
// `radflux solve`, `radflux viewfactors` and `radflux submit`.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"

namespace radflux {

struct ImportOptions {
  // Reflectance at or above this in a band is clamped to it (--max-reflectance).
  double max_reflectance = 0.98;
  // Refuse what the rules would fix (non-convex, non-planar, zero-area, Kd >= 1, ...) with
  // file:line, as before issue 19 (--strict).
  bool strict = false;
  // Every OBJ face is two back-to-back patches, each lit from its own side (--two-sided).
  bool two_sided = false;
  // Materials made emitters: name -> emitted radiance L_e per band, W/(m^2 sr) (--emit).
  std::vector<std::pair<std::string, Rgb>> emit;
  // Segments around a full circle when MGF primitives (sph, cyl, cone, ring, torus) are
  // tessellated (--curve-segments): a sphere gets n around and ceil(n/2) bands pole to pole,
  // a torus n x n; areas come out low by less than (pi/n)^2 (mgf_primitives.h).
  int curve_segments = 16;
};

// One --emit rule, MATERIAL=R,G,B (three numbers >= 0; the name may itself hold '='):
// the material's name and its radiance, or InvalidArgument quoting `value`.
absl::StatusOr<std::pair<std::string, Rgb>> ParseEmitRule(const std::string& value);

}  // namespace radflux
