// Lights for scenes that have none: --emit MATERIAL=R,G,B makes a material an emitter, and a
// scene without any emitter is refused with a message that says how to light it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "solver/core/bands.h"
#include "solver/scene/scene.h"

namespace radflux {

// Sets each named material's emission to pi * L_e (L_e: emitted radiance per band,
// W/(m^2 sr)). INVALID_ARGUMENT naming the material when the scene has none by that name,
// or when L_e is negative or not finite.
absl::Status ApplyEmitOptions(const std::vector<std::pair<std::string, Rgb>>& emit, Scene& scene);

// "scene.obj: no emitter (no face's material has Ke > 0); light it with --emit
// MATERIAL=R,G,B (emitted radiance L_e, repeatable); the materials with the largest area:
// 'a' (12.5), ..." naming at most five materials in use, largest total face area first
// (scene units^2).
std::string NoEmitterMessage(const Scene& scene);

}  // namespace radflux
