// Exposed fraction of an element: the share of its area not buried inside a closed solid
// (the floor under a block). Light reaches only that part and leaves only from it, so the
// hierarchical solver keeps radiosity per exposed area: a coarse floor element under which a
// block stands then does not dilute what it sends with the dark area the block covers.
#pragma once

#include <cstdint>
#include <span>

#include "solver/mesh/adaptive_tree.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

// Fraction of `samples` stratified points of `e` whose cosine-distributed ray (offset by
// ray_epsilon along the normal) escapes or first hits the front of a patch of `mesh` (the
// mesh `caster` was built on); a ray hitting a back side starts inside a solid, unless that
// patch is partly transparent (an alpha cut-out is a sheet, not a solid's wall). In [0, 1].
double ExposedFraction(const Element& e, const PatchMesh& mesh, const RayCaster& caster,
                       int samples, uint32_t pattern, double ray_epsilon);

}  // namespace radflux
