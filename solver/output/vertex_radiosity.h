// Per-vertex values of a PatchMesh, for Gouraud shading and mesh export, continuous
// across the faces that ShadingMesh welds. Each welded vertex takes, per band, the value
// at its position of the plane fitted by area-weighted least squares to its patches'
// values at their centroids: the patches around it for an interior vertex, those and
// their neighbours for a boundary vertex (so the value there is extrapolated from the
// inside, not averaged: a linear field is reproduced exactly everywhere the vertex lies
// within 4 standard deviations of the fit centroids' spread; beyond, in that direction the
// fit is flat, so no vertex's weights sum to more than 9 in absolute value). The fit smooths,
// so a peaked field's Gouraud picture would lose light; each patch's deficit (its value
// minus its Gouraud mean) is fitted the same way and added once, which leaves a deficit
// second order in the smoothing (Cornell back wall's picture mean: -2.3% -> -0.15%), and a
// damped least-squares matching of every shown patch's Gouraud mean to its value then takes
// most of what is left (gouraud_means.h: light stays in its patch). A vertex
// that a shown patch uses is fitted to shown patches only, never to hidden ones (Patch::hidden:
// the inside of a slot under an emitter, far brighter than what is seen beside it). A T-junction
// vertex then takes the linear interpolation along the edge it lies on, so both sides of
// that edge interpolate the same values.
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/shading_mesh.h"

namespace radflux {

// Radiosity per welded vertex (W/m^2 per band, >= 0) from radiosity per patch; one entry
// per shading.size(). Fails if the sizes disagree.
absl::StatusOr<std::vector<Rgb>> WeldedVertexRadiosity(const PatchMesh& mesh,
                                                       const ShadingMesh& shading,
                                                       const std::vector<Rgb>& patch_radiosity);

// The same, one entry per mesh.positions (a position takes its welded vertex's value).
absl::StatusOr<std::vector<Rgb>> VertexRadiosity(const PatchMesh& mesh, const ShadingMesh& shading,
                                                 const std::vector<Rgb>& patch_radiosity);

}  // namespace radflux
