// The emitters of a mesh as the final gather's light sampling sees them: every emitting face
// whose patches tile a convex triangle or quad becomes one light (the Cornell box's lamp, 12
// patches at the defaults, is one rectangle), so that choosing an emitter for a light sample
// weighs a few faces, not every patch of them; the patches of other emitting faces stay lights
// as they are. The lights cover exactly the emitting patches, with their emission.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/core/bands.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/patch_mesh.h"

namespace radflux {

struct GatherLights {
  PatchMesh mesh;                  // one patch per light, scene units
  std::vector<Rgb> emission;       // per light, W/m^2 per band
  std::vector<uint32_t> of_patch;  // per patch of the source mesh: its light, or kNoLight
};

inline constexpr uint32_t kNoLight = 0xffffffffu;

// The lights of `mesh` (patches with E > 0 in some band).
GatherLights MakeGatherLights(const PatchMesh& mesh, const PatchAttributes& attributes);

}  // namespace radflux
