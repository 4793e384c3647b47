// Scene validation: run before any work; the first problem found is returned as
// INVALID_ARGUMENT naming the file, line, face and what is wrong.
#pragma once

#include "absl/status/status.h"
#include "solver/scene/scene.h"

namespace radflux {

// A face vertex may lie at most this far from the face's plane, relative to the
// face's longest edge (the published Cornell red wall, 3.2 mm off over 560 mm, fails).
inline constexpr double kPlanarityTolerance = 1e-3;
// A face whose area is below this fraction of its longest edge squared is degenerate.
inline constexpr double kDegenerateAreaTolerance = 1e-9;

absl::Status ValidateScene(const Scene& scene);

// The checks of ValidateScene for one face (vertex count, finite, zero area, planar, convex)
// and one material (reflectance in [0,1), emission finite and >= 0), with its messages.
absl::Status ValidateFace(const Scene& scene, size_t f);
absl::Status ValidateMaterial(const Scene& scene, const Material& m);

}  // namespace radflux
