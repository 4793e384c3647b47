// The emitters as bench/object_reference samples them (issue 21): at each path vertex an
// emitting patch is chosen in proportion to an estimate of the irradiance it gives there
// unoccluded (positive wherever it can light the vertex), and a direction towards it uniform
// in the solid angle it subtends (Arvo's spherical triangles). The estimate of direct light
// then varies only with visibility, the cosine at the vertex and the estimate's error:
// a point 2 cm from a lamp (RenderPark's corridor) or one lit by one of 24 tubes inside
// housings (the classroom) is not a 1/r^2 tail nor a lottery over the scene's lamps.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/core/bands.h"
#include "solver/core/sampling.h"
#include "solver/core/vec3.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/scene/scene.h"

namespace radflux {

// The emitting patches of a mesh (one patch per face), with the per-vertex choice above.
class ReferenceEmitters {
 public:
  ReferenceEmitters(const Scene& scene, const PatchMesh& mesh);

  // One next-event sample: the emitter, the unit direction to a point on it, the distance
  // to that point, and the pdf (per steradian) of the whole choice. pdf == 0: no sample.
  struct Sample {
    uint32_t patch = 0;
    Vec3 direction;
    double distance = 0;
    double pdf = 0;
  };

  size_t size() const { return patches_.size(); }
  // Each emitter's weight at x (normal n): about its unoccluded form factor x luminance of E;
  // `weights` is resized to size(). Returns their sum (0: no emitter can light x).
  double Weights(const Vec3& x, const Vec3& n, std::vector<double>& weights) const;
  // A sample towards an emitter chosen in proportion to `weights` (summing to `total` > 0).
  Sample Draw(const Vec3& x, const std::vector<double>& weights, double total, double u_pick,
              Point2 u) const;
  // The pdf per steradian with which Draw (with weights summing to `total`) picks the
  // direction from x to emitter patch `patch` (n: x's normal); for MIS weights, where a
  // quad's two triangles count as one solid angle.
  double Pdf(uint32_t patch, const Vec3& x, const Vec3& n, double total) const;
  // True when `patch` emits.
  bool Emits(uint32_t patch) const { return index_[patch] >= 0; }

 private:
  double Weight(size_t k, const Vec3& x, const Vec3& n) const;
  // The solid angles of emitter k's (one or two) triangles seen from x.
  std::array<double, 2> SolidAngles(size_t k, const Vec3& x) const;

  const PatchMesh& mesh_;
  std::vector<uint32_t> patches_;    // emitting patches
  std::vector<double> luminance_;    // per emitter: mean of E's bands
  std::vector<int32_t> index_;       // per patch: its emitter index, or -1
};

}  // namespace radflux
