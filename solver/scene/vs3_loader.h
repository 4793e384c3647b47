// View3D's `.vs3` input (NIST/NREL View3D 3.2, "vertex/surface" format 3) into a radflux Scene.
//
// Records, one per line, identified by their first character (case-insensitive), as View3D's
// GetVS3D reads them:
//   T title                       the model's title (kept in Vs3Model::title)
//   F 3                           the geometry format; only 3 (vertex/surface) exists here
//   C key=value ...               run control (Vs3Control; separators '=', ' ', ',')
//   V n x y z                     vertex n (1, 2, 3, ... in order)
//   S n v1 v2 v3 v4 base cmbn emit name
//                                 radiating surface n (numbered with the O surfaces, all S
//                                 first); v4 = 0 for a triangle; vertices counter-clockwise
//                                 seen from the side that sees the others; emittance emit
//                                 clamped to [0.001, 0.999] as View3D does
//   O n v1 v2 v3 v4               obstruction-only surface: blocks, has no view factors
//   E (or *)                      end of data; anything after it is ignored
//   / or !                        comment; X (a transformation View3D also ignores) skipped
// Surfaces with a base or combine surface (subsurfaces, combining) and M/N (mask, null)
// surfaces, and format 3a, are refused with file:line: radflux does not implement them.
//
// Each S surface becomes one object (its name; a repeated name gets "#n", n its surface
// number) and one face with a material "emit=<e>" of reflectance 1 - e; each O surface a face
// with Face::obstruction set, in object "obstruction#n". Errors: INVALID_ARGUMENT with one
// line "file:line: what is wrong".
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/scene.h"

namespace radflux {

// View3D's run-control values (C record), with View3D's defaults.
struct Vs3Control {
  bool enclosure = false;   // encl: the surfaces form an enclosure (rows are normalised)
  bool emittances = false;  // emit: View3D would include emissivities (interchange factors)
  double eps = 1e-4;        // epsAdap: View3D's adaptive-integration convergence limit
  int max_u = 12;           // maxU: View3D's maximum unobstructed recursions
  int max_o = 8;            // maxO: maximum obstructed recursions
  int min_o = 0;            // minO: minimum obstructed recursions
  int row = 0, col = 0;     // View3D computes only this row / element when > 0
  int out = 0;              // View3D's output format: 0 text, 1 binary
  int list = 0;             // View3D's log detail
  bool prj_reverse = false; // prjD: View3D's projection direction choice
};

struct Vs3Model {
  Scene scene;
  std::string title;
  Vs3Control control;
};

// The model in the .vs3 file `path`.
absl::StatusOr<Vs3Model> LoadVs3File(const std::string& path);

// The model in .vs3 `text`, named `name` in messages.
absl::StatusOr<Vs3Model> LoadVs3Text(const std::string& text, const std::string& name);

}  // namespace radflux
