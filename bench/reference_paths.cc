#include "bench/reference_paths.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "solver/core/sampling.h"
#include "solver/formfactor/row_builder.h"
#include "solver/mesh/subdivide.h"

namespace radflux {
namespace {

// Next-event samples per path vertex (their mean).
constexpr int kLightSamples = 2;
// The largest share of continuation directions that go to the guide's points (the rest:
// cosine). At a vertex of reflectance rho it is at most 1 - rho, so that a cosine direction's
// weight 1 / (1 - share) times rho stays <= 1: a path bouncing inside a lamp housing, where
// the guide's points are far off in solid angle, does not grow without bound.
constexpr double kGuideShare = 0.5;

double Uniform(ReferenceRng& rng) { return std::uniform_real_distribution<double>(0, 1)(rng); }

// The index at which u (in [0, 1)) falls in a running sum ending at 1.
size_t Pick(const std::vector<double>& cdf, double u) {
  return std::min<size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin(),
                          cdf.size() - 1);
}

// The running sum of `weight`, scaled to end at 1 (empty when they sum to 0).
std::vector<double> NormalisedCdf(const std::vector<double>& weight) {
  std::vector<double> cdf;
  double sum = 0;
  for (double w : weight) cdf.push_back(sum += w);
  if (!(sum > 0)) return {};
  for (double& c : cdf) c /= sum;
  return cdf;
}

}  // namespace

ReferenceTracer::ReferenceTracer(const Scene& scene, PatchMesh mesh)
    : scene_(scene), mesh_(std::move(mesh)), emitters_(scene_, mesh_) {}

absl::StatusOr<std::unique_ptr<ReferenceTracer>> ReferenceTracer::Create(const Scene& scene) {
  MeshOptions one_per_face;
  one_per_face.follow_contacts = false;
  auto mesh = SubdivideScene(scene, one_per_face);
  if (!mesh.ok()) return mesh.status();
  std::unique_ptr<ReferenceTracer> tracer(new ReferenceTracer(scene, std::move(*mesh)));
  auto caster = EmbreeRayCaster::Create(tracer->mesh_);
  if (!caster.ok()) return caster.status();
  tracer->caster_ = std::move(*caster);
  const PatchMesh& m = tracer->mesh_;
  tracer->epsilon_ = RayEpsilonFor(m);  // the rows' lift: a convention of geometry, not a method
  std::vector<double> power(m.size());
  for (uint32_t p = 0; p < m.size(); ++p)
    power[p] =
        m.patches[p].opacity * m.patches[p].area * MeanComponent(tracer->MaterialOf(p).emission);
  for (double w : power) tracer->emitted_power_ += w;
  tracer->emitter_cdf_ = NormalisedCdf(power);
  return tracer;
}

void ReferenceTracer::SetGuide(const std::vector<double>& weight) {
  guide_cdf_ = NormalisedCdf(weight);
  guide_pick_.assign(mesh_.size(), 0.0);
  for (size_t p = 0; p < guide_cdf_.size(); ++p)
    guide_pick_[p] = guide_cdf_[p] - (p ? guide_cdf_[p - 1] : 0.0);
}

double ReferenceTracer::GuideShare(uint32_t p) const {
  if (guide_cdf_.empty()) return 0;
  return std::clamp(1 - MeanComponent(MaterialOf(p).reflectance), 0.0, kGuideShare);
}

double ReferenceTracer::ContinuationPdf(double share, const Vec3& x, const Vec3& n, const Vec3& w,
                                        const Vec3& y, uint32_t q) const {
  const double cosine = std::max(0.0, Dot(n, w)) * std::numbers::inv_pi;
  if (share <= 0) return cosine;
  double guided = 0;
  if (q != kNoPatch && guide_pick_[q] > 0) {
    const Vec3 d = y - x;
    const double facing = -Dot(mesh_.patches[q].normal, w);
    if (facing > 0) guided = guide_pick_[q] / mesh_.patches[q].area * Dot(d, d) / facing;
  }
  return (1 - share) * cosine + share * guided;
}

Rgb ReferenceTracer::DirectIrradiance(double share, const Vec3& x, const Vec3& n,
                                      const std::vector<double>& weights, double total,
                                      ReferenceRng& rng) const {
  Rgb h{};
  if (!(total > 0)) return h;
  for (int k = 0; k < kLightSamples; ++k) {
    const double u_pick = Uniform(rng);
    const auto s = emitters_.Draw(x, weights, total, u_pick, {Uniform(rng), Uniform(rng)});
    const double cx = s.pdf > 0 ? Dot(n, s.direction) : 0;
    if (cx <= 0) continue;
    // The shadow ray runs on to the emitter and is blocked only by another patch met first:
    // stopped short of it by 1e-5 of the distance, Embree's single precision still met the
    // emitter itself on 3.8% of the rays from a ceiling 2 cm above a lamp (the ceiling read
    // 1.2% low against C-11, object_reference_check.py case 3; the same at ten times the scale).
    const double reach = s.distance * (1 - 1e-5) - 4 * epsilon_;
    if (reach <= 0) continue;
    const Hit hit = caster_->Intersect(
        {x + n * epsilon_, s.direction, 0, s.distance * (1 + 1e-5) + 4 * epsilon_});
    if (hit.patch != kNoPatch && hit.patch != s.patch && hit.t < reach) continue;
    const Vec3 y = x + s.direction * s.distance;
    const double light = emitters_.Pdf(s.patch, x, n, total);
    const double weight = light / (light + ContinuationPdf(share, x, n, s.direction, y, s.patch));
    const double g = cx / s.pdf * std::numbers::inv_pi * weight / kLightSamples;
    // Only the emitter's opaque part emits (a continuation meets it with that probability).
    const double opacity = mesh_.patches[s.patch].opacity;
    const Rgb& e = MaterialOf(s.patch).emission;
    for (int c = 0; c < kBands; ++c) h[c] += e[c] * g * opacity;
  }
  return h;
}

ReferenceTracer::Continuation ReferenceTracer::Continue(double share, const Vec3& x, const Vec3& n,
                                                        ReferenceRng& rng) const {
  if (share > 0 && Uniform(rng) < share) {
    const uint32_t q = static_cast<uint32_t>(Pick(guide_cdf_, Uniform(rng)));
    const PatchPointSampler sample(mesh_, q);
    const Vec3 d = sample({Uniform(rng), Uniform(rng)}) - x;
    return {Normalize(d), q, Length(d)};
  }
  return {Frame::FromNormal(n).ToWorld(SampleCosineHemisphere({Uniform(rng), Uniform(rng)})),
          kNoPatch, 0};
}

Rgb ReferenceTracer::ReflectedRadiosity(uint32_t p, Vec3 x, ReferenceRng& rng) const {
  Rgb b{};
  Rgb throughput = MaterialOf(p).reflectance;
  const double first = MaxComponent(throughput);
  if (!(first > 0)) return b;
  std::vector<double> weights;
  for (int bounce = 0;; ++bounce) {
    const Vec3 n = mesh_.patches[p].normal;
    const double total = emitters_.Weights(x, n, weights);
    const double share = GuideShare(p);
    const Rgb direct = DirectIrradiance(share, x, n, weights, total, rng);
    for (int c = 0; c < kBands; ++c) b[c] += throughput[c] * direct[c];
    if (bounce >= 3) {
      // Relative to the first reflectance: a dark object's paths (a table frame of rho 0.1)
      // are not cut at once and the few survivors weighted up tenfold.
      const double survive = std::min(0.95, MaxComponent(throughput) / first);
      if (Uniform(rng) >= survive) break;
      for (double& t : throughput) t /= survive;
    }
    // The mixture samples points: a guided point that is not the first surface along its
    // direction (hidden, or a back side) adds nothing, as its integrand is zero there.
    const Continuation next = Continue(share, x, n, rng);
    const Vec3& w = next.direction;
    const double cx = Dot(n, w);
    if (cx <= 0) break;
    const Hit hit = caster_->Intersect({x + n * epsilon_, w, 0, INFINITY});
    if (hit.patch == kNoPatch || Dot(hit.normal, w) >= 0) break;  // escaped or a back side
    if (next.target != kNoPatch &&
        (hit.patch != next.target ||
         std::abs(hit.t - next.distance) > 1e-4 * next.distance + 2 * epsilon_))
      break;
    const Vec3 y = x + n * epsilon_ + w * hit.t;
    const double pdf = ContinuationPdf(share, x, n, w, y, hit.patch);
    if (!(pdf > 0)) break;
    const double scale = cx * std::numbers::inv_pi / pdf;
    for (double& t : throughput) t *= scale;
    if (emitters_.Emits(hit.patch)) {  // the continuation's share of the emitter's light
      const double light = emitters_.Pdf(hit.patch, x, n, total);
      const double weight = pdf / (pdf + light);
      const Rgb& e = MaterialOf(hit.patch).emission;
      for (int c = 0; c < kBands; ++c) b[c] += throughput[c] * e[c] * weight;
    }
    p = hit.patch;
    x = y;
    const Rgb& rho = MaterialOf(p).reflectance;
    for (int c = 0; c < kBands; ++c) throughput[c] *= rho[c];
  }
  return b;
}

void ReferenceTracer::TraceParticle(ReferenceRng& rng, std::vector<double>& incident) const {
  if (emitter_cdf_.empty()) return;
  uint32_t p = static_cast<uint32_t>(Pick(emitter_cdf_, Uniform(rng)));
  const PatchPointSampler sample(mesh_, p);
  Vec3 x = sample({Uniform(rng), Uniform(rng)});
  for (;;) {
    const Vec3 n = mesh_.patches[p].normal;
    const Vec3 w =
        Frame::FromNormal(n).ToWorld(SampleCosineHemisphere({Uniform(rng), Uniform(rng)}));
    const Hit hit = caster_->Intersect({x + n * epsilon_, w, 0, INFINITY});
    if (hit.patch == kNoPatch || Dot(hit.normal, w) >= 0) return;
    incident[hit.patch] += 1;
    x = x + n * epsilon_ + w * hit.t;
    p = hit.patch;
    if (Uniform(rng) >= MeanComponent(MaterialOf(p).reflectance)) return;
  }
}

ReferenceTracer::Loss ReferenceTracer::TraceLoss(ReferenceRng& rng) const {
  Loss loss;
  if (emitter_cdf_.empty()) return loss;
  uint32_t p = static_cast<uint32_t>(Pick(emitter_cdf_, Uniform(rng)));
  const Rgb& e = MaterialOf(p).emission;
  Rgb weight{};
  for (int c = 0; c < kBands; ++c) weight[c] = e[c] / MeanComponent(e);
  loss.emitted = weight;
  Vec3 x = PatchPointSampler(mesh_, p)({Uniform(rng), Uniform(rng)});
  for (bool first_flight = true;; first_flight = false) {
    const Vec3 n = mesh_.patches[p].normal;
    if (!first_flight && MaxComponent(MaterialOf(p).emission) > 0) {
      for (int c = 0; c < kBands; ++c) loss.reflected_by_emitters[c] += weight[c];
    }
    const Vec3 w =
        Frame::FromNormal(n).ToWorld(SampleCosineHemisphere({Uniform(rng), Uniform(rng)}));
    const Hit hit = caster_->Intersect({x + n * epsilon_, w, 0, INFINITY});
    if (hit.patch == kNoPatch || Dot(hit.normal, w) >= 0) {
      const bool from_emitter = MaxComponent(MaterialOf(p).emission) > 0;
      for (int c = 0; c < kBands; ++c) {
        loss.lost[c] += weight[c];
        if (from_emitter) loss.lost_leaving_emitters[c] += weight[c];
        if (first_flight) loss.lost_first_flight[c] += weight[c];
      }
      loss.from_patch = p;
      return loss;
    }
    x = x + n * epsilon_ + w * hit.t;
    p = hit.patch;
    for (int c = 0; c < kBands; ++c) weight[c] *= MaterialOf(p).reflectance[c];
    const double survive = std::min(1.0, MaxComponent(weight));
    if (!(survive > 0) || Uniform(rng) >= survive) return loss;
    for (double& v : weight) v /= survive;
  }
}

int TakeEmitFlags(int argc, char** argv, ImportOptions& import) {
  int first = 1;
  for (; first + 1 < argc && std::string(argv[first]) == "--emit"; first += 2) {
    auto rule = ParseEmitRule(argv[first + 1]);
    if (!rule.ok()) {
      std::fprintf(stderr, "%s\n", rule.status().ToString().c_str());
      return -1;
    }
    import.emit.push_back(*std::move(rule));
  }
  return first;
}

std::vector<double> ParticleGuide(const ReferenceTracer& tracer, uint64_t seed, int particles) {
  const size_t n = tracer.mesh().size();
  std::vector<double> incident(n, 0.0);
#pragma omp parallel
  {
    std::vector<double> mine(n, 0.0);
    ReferenceRng rng(seed * 0x2545F4914F6CDD1Dull + static_cast<uint64_t>(omp_get_thread_num()));
#pragma omp for schedule(static)
    for (int i = 0; i < particles; ++i) tracer.TraceParticle(rng, mine);
#pragma omp critical
    for (size_t p = 0; p < n; ++p) incident[p] += mine[p];
  }
  for (uint32_t p = 0; p < n; ++p) {
    const Rgb& rho = tracer.MaterialOf(p).reflectance;
    incident[p] *= (rho[0] + rho[1] + rho[2]) / 3;
  }
  return incident;
}

}  // namespace radflux
