// The measurements every face check and import rule shares: area, plane, planarity and
// convexity of one polygon, with the tolerances of validation.h. One definition, so that
// what the import rules fix is exactly what validation would refuse.
#pragma once

#include <vector>

#include "solver/core/vec3.h"

namespace radflux {

struct FaceShape {
  Vec3 normal;                 // unit Newell normal; zero when the face is degenerate
  double area = 0;             // scene units^2 (Newell: exact for a planar polygon)
  double longest_edge = 0;     // scene units
  double planarity_error = 0;  // largest vertex distance from the plane through the centroid
  bool finite = true;          // every coordinate finite
  bool degenerate = false;     // area <= kDegenerateAreaTolerance * longest_edge^2
  bool planar = true;          // planarity_error <= kPlanarityTolerance * longest_edge
  bool convex = true;          // no reflex corner (tested only when planar and not degenerate)
};

// Measures `polygon` (at least 3 vertices, counter-clockwise seen from the front).
FaceShape MeasureFace(const std::vector<Vec3>& polygon);

}  // namespace radflux
