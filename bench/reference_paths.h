// The path tracer of bench/object_reference (issue 21): the reflected radiosity rho(x) H(x)
// at a surface point, unbiased, with nothing of the radiosity solver in it (no unknowns, no
// form factors, no grouping): only the loader's faces, Embree, and closed forms for the
// direct light of a polygon.
//
// Conventions are radflux's: faces are single-sided (a ray meeting a back side ends: it
// absorbs), emitters emit from their front only, reflectance is Lambertian and clamped as
// on import; a partly transparent face (Patch::opacity < 1) lets a ray through as the ray
// casters do, and emits from its opaque part only. Per path vertex: kLightSamples
// next-event samples (ReferenceEmitters: emitter by unoccluded irradiance, direction uniform
// in its solid angle), a continuation direction
// from a mixture of the cosine and of the `guide` (points on bright surfaces, in proportion
// to their reflected power: the lamp housings that light RenderPark's classroom are a small,
// bright target a cosine bounce rarely finds), emitted light met by the continuation and by
// next-event samples combined by the balance heuristic; Russian roulette after 3 bounces.
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "absl/status/statusor.h"
#include "bench/reference_emitters.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/raytrace/ray_caster.h"
#include "solver/scene/import_options.h"
#include "solver/scene/scene.h"

namespace radflux {

using ReferenceRng = std::mt19937_64;

class ReferenceTracer;
// The bench tools' leading `--emit MATERIAL=R,G,B` flags (as radflux's) into import.emit:
// the index of the first other argument, or -1 after saying on stderr which rule is bad.
int TakeEmitFlags(int argc, char** argv, ImportOptions& import);

// Per patch, its reflected power as `particles` particles from the emitters find it
// (relative units), on all threads: the guide object_reference and reference_image set.
std::vector<double> ParticleGuide(const ReferenceTracer& tracer, uint64_t seed, int particles);

// A scene as the reference traces it: one patch per face (or a fan), Embree, the emitters.
class ReferenceTracer {
 public:
  // Loads nothing itself: `scene` must outlive the tracer.
  static absl::StatusOr<std::unique_ptr<ReferenceTracer>> Create(const Scene& scene);

  const PatchMesh& mesh() const { return mesh_; }
  const Material& MaterialOf(uint32_t patch) const {
    return scene_.materials[scene_.faces[mesh_.patches[patch].face].material];
  }
  // Sets the guide: per patch a non-negative weight (its reflected power, say); continuation
  // directions then go, with probability GuideShare, to a point uniform by area on a patch
  // chosen in proportion to it. All zero or empty: cosine continuations only.
  void SetGuide(const std::vector<double>& weight);
  // One path's estimate of rho(x) H(x) per band at point x of patch p (W/m^2 per band).
  Rgb ReflectedRadiosity(uint32_t p, Vec3 x, ReferenceRng& rng) const;
  // One particle from the emitters (chosen by power, cosine-distributed, reflected with
  // probability of its reflectance's mean): adds to `incident` (per patch) the power it
  // brings to each patch it meets, in units of the scene's total emitted power / particles.
  void TraceParticle(ReferenceRng& rng, std::vector<double>& incident) const;
  // Where one particle's light ends that no front side takes in: per band, its share of the
  // particle's power (start E_b / mean E over bands) lost on a back side or in the void, and
  // of it, what was lost on a flight from an emitter's face (and on the emitted flight itself,
  // before any reflection), and that flight's patch. Reflected
  // with the band's rho (Russian roulette on the largest band's weight). The means over many
  // particles are shares of the emitted power.
  struct Loss {
    Rgb emitted{};  // the particle's starting weight per band (its band's share of the power)
    Rgb lost{}, lost_leaving_emitters{}, lost_first_flight{};
    Rgb reflected_by_emitters{};  // the power it carried on flights that left an emitter's
                                  // face after a reflection there
    uint32_t from_patch = kNoPatch;  // one particle's: the patch its lost flight left
  };
  Loss TraceLoss(ReferenceRng& rng) const;

 private:
  ReferenceTracer(const Scene& scene, PatchMesh mesh);
  // Next-event estimates of the direct irradiance at x (normal n) per band, MIS-weighted
  // against the continuation; `total` is the emitters' summed weight at x.
  Rgb DirectIrradiance(double share, const Vec3& x, const Vec3& n,
                       const std::vector<double>& weights, double total, ReferenceRng& rng) const;
  // The share of continuations from a vertex on patch p that follow the guide.
  double GuideShare(uint32_t p) const;
  // The continuation's pdf per steradian of direction w (unit) from x (normal n, guide share
  // `share`) towards point y of patch q (q == kNoPatch: y is not on a guided patch).
  double ContinuationPdf(double share, const Vec3& x, const Vec3& n, const Vec3& w, const Vec3& y,
                         uint32_t q) const;
  // A continuation from x (normal n): a unit direction, and for a guided one the patch and
  // distance of the point it aims at (target kNoPatch: a cosine direction).
  struct Continuation {
    Vec3 direction;
    uint32_t target = kNoPatch;
    double distance = 0;
  };
  Continuation Continue(double share, const Vec3& x, const Vec3& n, ReferenceRng& rng) const;

  const Scene& scene_;
  PatchMesh mesh_;
  std::unique_ptr<EmbreeRayCaster> caster_;
  ReferenceEmitters emitters_;
  double epsilon_ = 0;               // ray offset, scene units
  std::vector<double> guide_cdf_;    // running sum of the guide's weights, ends at 1
  std::vector<double> guide_pick_;   // per patch: its probability of being the guide's pick
  double emitted_power_ = 0;         // sum over emitters of area x mean E
  std::vector<double> emitter_cdf_;  // by power, ends at 1 (the particles' start)
};

}  // namespace radflux
