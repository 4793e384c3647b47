// Duplicate faces: the same polygon (the same vertex positions in the same cyclic order,
// facing the same way) listed twice, a common export artefact. Found by hashing each face's
// canonical vertex cycle and sorting, O(n log n).
#pragma once

#include <cstdint>
#include <vector>

#include "solver/scene/scene.h"

namespace radflux {

// Indices of faces that repeat an earlier face exactly (positions compared bit for bit,
// whatever the vertex indices; a face and its reverse are not duplicates), ascending.
std::vector<uint32_t> FindDuplicateFaces(const Scene& scene);

}  // namespace radflux
