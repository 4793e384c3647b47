// Two-sided surfaces: a face whose material is two-sided becomes two back-to-back faces,
// itself and its twin (the same vertices in reverse order), each lit from its own side.
// The ray casters ignore hits on the back of a two-sided patch, so the twins never shade
// each other and a ray meets the side that faces it (see EmbreeRayCaster).
#pragma once

#include <cstdint>

#include "solver/scene/scene.h"

namespace radflux {

// Appends the twin of every face whose material has two_sided set, after all the faces,
// with the same material, object, group and source line, marked back_face. Returns how many
// were added.
uint64_t AddBackFaces(Scene& scene);

}  // namespace radflux
