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
#include "solver/output/gouraud_means.h"
#include "solver/output/shading_mesh.h"

namespace radflux {

// The fit above for one mesh, built once (its weights and the Gouraud means' are geometry)
// and applied to any field per patch: the default picture interpolates two (B - E where its
// gather rays land, and the indirect light it shows). The mesh and shading mesh must outlive it.
class VertexFit {
 public:
  // A vertex's value as a linear combination of its fit patches' values.
  struct Weights {
    std::vector<uint32_t> patches;
    std::vector<double> weights;  // one per patch; they sum to 1
  };
  // Fails if `shading` was built for another mesh.
  static absl::StatusOr<VertexFit> Build(const PatchMesh& mesh, const ShadingMesh& shading);
  // Per welded vertex / per mesh position, as the functions below; fails on a size mismatch.
  absl::StatusOr<std::vector<Rgb>> Welded(const std::vector<Rgb>& patch_radiosity) const;
  absl::StatusOr<std::vector<Rgb>> AtPositions(const std::vector<Rgb>& patch_radiosity) const;

 private:
  VertexFit(const PatchMesh& mesh, const ShadingMesh& shading);
  const PatchMesh* mesh_;
  const ShadingMesh* shading_;
  std::vector<Weights> fits_;  // per welded vertex
  GouraudMeans means_;
};

// Radiosity per welded vertex (W/m^2 per band, >= 0) from radiosity per patch; one entry
// per shading.size(). Fails if the sizes disagree.
absl::StatusOr<std::vector<Rgb>> WeldedVertexRadiosity(const PatchMesh& mesh,
                                                       const ShadingMesh& shading,
                                                       const std::vector<Rgb>& patch_radiosity);

// The same, one entry per mesh.positions (a position takes its welded vertex's value).
absl::StatusOr<std::vector<Rgb>> VertexRadiosity(const PatchMesh& mesh, const ShadingMesh& shading,
                                                 const std::vector<Rgb>& patch_radiosity);

}  // namespace radflux
