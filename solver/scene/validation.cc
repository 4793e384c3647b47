#include "solver/scene/validation.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "solver/scene/emitters.h"
#include "solver/scene/face_shape.h"

namespace radflux {
namespace {

absl::Status FaceError(const Scene& scene, size_t f, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(scene.DescribeFace(f), ": ", what));
}

}  // namespace

absl::Status ValidateMaterial(const Scene& scene, const Material& m) {
  for (int b = 0; b < kBands; ++b) {
    const double rho = m.reflectance[b], e = m.emission[b];
    if (!std::isfinite(rho) || rho < 0 || rho >= 1) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "%s: material '%s': reflectance Kd %g is outside [0,1)", scene.source, m.name, rho));
    }
    if (!std::isfinite(e) || e < 0) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "%s: material '%s': emission Ke %g must be finite and >= 0", scene.source, m.name,
          e / 3.141592653589793));
    }
  }
  return absl::OkStatus();
}

absl::Status ValidateFace(const Scene& scene, size_t f) {
  const Face& face = scene.faces[f];
  if (face.vertices.size() < 3) return FaceError(scene, f, "a face needs at least 3 vertices");
  const FaceShape shape = MeasureFace(FacePolygon(scene, face));
  if (!shape.finite) return FaceError(scene, f, "vertex has a NaN or infinite coordinate");
  if (shape.degenerate) {
    return FaceError(scene, f, absl::StrFormat("zero-area (degenerate) face, area %g", shape.area));
  }
  if (!shape.planar) {
    const double tolerance = kPlanarityTolerance * shape.longest_edge;
    return FaceError(scene, f,
                     absl::StrFormat("non-planar face: a vertex is %g off its plane (tolerance "
                                     "%g = %g x longest edge); split it into triangles",
                                     shape.planarity_error, tolerance, kPlanarityTolerance));
  }
  if (!shape.convex) return FaceError(scene, f, "non-convex face; split it into convex polygons");
  return absl::OkStatus();
}

absl::Status ValidateScene(const Scene& scene) {
  if (scene.faces.empty()) return absl::InvalidArgumentError(scene.source + ": empty scene (no faces)");
  bool has_emitter = false;
  std::vector<bool> checked(scene.materials.size(), false);  // only materials in use matter
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const uint32_t material = scene.faces[f].material;
    if (material >= scene.materials.size()) return FaceError(scene, f, "unknown material");
    if (!checked[material]) {
      checked[material] = true;
      if (absl::Status s = ValidateMaterial(scene, scene.materials[material]); !s.ok()) return s;
    }
    if (absl::Status s = ValidateFace(scene, f); !s.ok()) return s;
    has_emitter = has_emitter || scene.materials[scene.faces[f].material].IsEmitter();
  }
  if (!has_emitter) {
    return absl::InvalidArgumentError(NoEmitterMessage(scene));
  }
  return absl::OkStatus();
}

}  // namespace radflux
