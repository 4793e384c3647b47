// The triangles of a glTF mesh primitive from its vertex indices and mode, in the order and
// winding the glTF 2.0 spec gives (counter-clockwise front faces, as radflux's).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"

namespace radflux {

using Triangle = std::array<uint32_t, 3>;

// Whether `mode` (TINYGLTF_MODE_*, -1 = unset = TRIANGLES) draws surfaces: TRIANGLES,
// TRIANGLE_STRIP or TRIANGLE_FAN.
bool IsSurfaceMode(int mode);

// How many triangles `count` indices draw in surface mode `mode` (AssembleTriangles' size).
size_t TriangleCount(int mode, size_t count);

// The triangles `indices` draw in surface mode `mode`: TRIANGLES takes them three at a time
// (a partial last triple is ignored), TRIANGLE_STRIP gives triangle i as
// (i, i + 1 + i % 2, i + 2 - i % 2) and TRIANGLE_FAN as (i + 1, i + 2, 0), as the spec does.
// Triangles with a repeated index (strip restarts) are kept; the caller decides.
std::vector<Triangle> AssembleTriangles(int mode, const std::vector<uint32_t>& indices);

}  // namespace radflux
