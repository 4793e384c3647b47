// object_reference SCENE PATHS SEED > REF.csv: an independent per-object reference for a
// scene's mean radiosity, by path tracing, for bench/real_scenes.py (issue 21).
//
// Nothing of the radiosity solver is used: no patches as unknowns, no form factors, no
// grouping. Only the loader (the faces radflux sees) and Embree (one primitive per face, or a
// fan for a larger polygon) are shared. Conventions are radflux's: faces are single-sided
// (a ray meeting a back side ends, it absorbs), emitters emit from their front only,
// reflectance is Lambertian and clamped as on import.
//
// Per object: its area mean of E exactly, plus the mean of rho(x) H(x) over PATHS points x
// uniform by area over its faces (stratified: the i-th in the i-th PATHS-quantile of area),
// H by a path with next-event estimation (kLightSamples emitter points per bounce, chosen by
// emitted power, with shadow rays) and cosine-distributed bounces, the two combined by MIS;
// Russian roulette after 3 bounces. Checked: a closed box of E = pi, rho = 0.5 gives 2 pi
// within 0.15% (1.7 standard errors; one light sample: 0.01%); the Cornell box's surfaces
// agree with radflux at 20,000 patches within 0.6% (the floor aside: radflux leaves out the
// part under the blocks).
// The estimator is unbiased; its own noise is printed per object as the standard error of
// independent paths (the stratification makes the true one smaller: two seeds tell it).
// Output rows: object,area,r,g,b,stderr (area-weighted mean B per band, W/m^2 per band;
// stderr of (r+g+b)/3).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/scene/load_scene.h"

namespace radflux {
namespace {

// The scene's faces as one patch each (or a fan), with what a path needs per patch.
struct TraceScene {
  const Scene& scene;
  PatchMesh mesh;
  std::unique_ptr<EmbreeRayCaster> caster;
  std::vector<uint32_t> emitters;    // emitting patches
  std::vector<double> emitter_cdf;   // by emitted power (area x mean E), ends at 1
  std::vector<double> emitter_pick;  // per patch: probability of being the emitter picked
  double epsilon = 0;                // ray offset, scene units

  const Material& MaterialOf(uint32_t p) const {
    return scene.materials[scene.faces[mesh.patches[p].face].material];
  }
};

using Rng = std::mt19937_64;

// Next-event samples per path vertex (their mean): a quarter of the noise of one.
constexpr int kLightSamples = 4;
double Uniform(Rng& rng) { return std::uniform_real_distribution<double>(0, 1)(rng); }

// A point uniform by area on patch p.
Vec3 PointOn(const TraceScene& ts, uint32_t p, Rng& rng) {
  const PatchPointSampler sample(ts.mesh, p);
  return sample({Uniform(rng), Uniform(rng)});
}

// Solid-angle pdf of next-event estimation choosing the point of emitter patch e seen from
// x along d (to the point; unnormalised): its pick probability / area, times r^2 / cos.
double LightPdf(const TraceScene& ts, uint32_t e, const Vec3& d) {
  const double r2 = Dot(d, d);
  const double cy = -Dot(ts.mesh.patches[e].normal, d) / std::sqrt(r2);
  return ts.emitter_pick[e] / ts.mesh.patches[e].area * r2 / cy;
}

// Multiple importance sampling (balance heuristic) of next-event estimation and cosine
// bounces: each technique's weight for a direction with the two solid-angle pdfs. Without
// it, a point 2 cm above a lamp (RenderPark's corridor) is all 1/r^2 tail.
double BalanceWeight(double pdf, double other) { return pdf / (pdf + other); }

// One next-event sample of the direct irradiance at x (normal n): an emitter point chosen
// by power, its radiance L_e = E / pi, the geometry term over its pdf, MIS-weighted against
// cosine bounces; zero when occluded or when either side faces away.
Rgb DirectIrradiance(const TraceScene& ts, const Vec3& x, const Vec3& n, Rng& rng) {
  const double u = Uniform(rng);
  const size_t k = std::min<size_t>(
      std::lower_bound(ts.emitter_cdf.begin(), ts.emitter_cdf.end(), u) - ts.emitter_cdf.begin(),
      ts.emitters.size() - 1);
  const uint32_t e = ts.emitters[k];
  const Patch& ep = ts.mesh.patches[e];
  const double pick = ts.emitter_pick[e];
  const Vec3 y = PointOn(ts, e, rng);
  const Vec3 d = y - x;
  const double r2 = Dot(d, d);
  const double cx = Dot(n, d), cy = -Dot(ep.normal, d);
  if (cx <= 0 || cy <= 0 || r2 <= 0) return {};
  Ray shadow{x + n * ts.epsilon, d, 0, 1 - 1e-5};
  if (ts.caster->Occluded(shadow)) return {};
  const double bounce_pdf = cx / std::sqrt(r2) * std::numbers::inv_pi;
  const double g = cx * cy / (r2 * r2) * ep.area / pick * std::numbers::inv_pi *
                   BalanceWeight(LightPdf(ts, e, d), bounce_pdf);
  const Rgb& E = ts.MaterialOf(e).emission;
  return {E[0] * g, E[1] * g, E[2] * g};
}

// Reflected radiosity rho H at point x of patch p, along one path.
Rgb ReflectedRadiosity(const TraceScene& ts, uint32_t p, Vec3 x, Rng& rng) {
  Rgb b{};
  Rgb throughput = ts.MaterialOf(p).reflectance;
  for (int bounce = 0;; ++bounce) {
    const Vec3 n = ts.mesh.patches[p].normal;
    for (int k = 0; k < kLightSamples; ++k) {
      const Rgb direct = DirectIrradiance(ts, x, n, rng);
      for (int c = 0; c < kBands; ++c) b[c] += throughput[c] * direct[c] / kLightSamples;
    }
    if (bounce >= 3) {
      const double survive = std::min(0.95, MaxComponent(throughput));
      if (Uniform(rng) >= survive) break;
      for (double& t : throughput) t /= survive;
    }
    const Vec3 w =
        Frame::FromNormal(n).ToWorld(SampleCosineHemisphere({Uniform(rng), Uniform(rng)}));
    const Hit hit = ts.caster->Intersect({x + n * ts.epsilon, w, 0, INFINITY});
    if (hit.patch == kNoPatch || Dot(hit.normal, w) >= 0) break;  // escaped or a back side
    const Vec3 y = x + n * ts.epsilon + w * hit.t;
    p = hit.patch;
    const Rgb& E = ts.MaterialOf(p).emission;
    if (MaxComponent(E) > 0) {  // the bounce's share of the emitter's light
      const double weight = BalanceWeight(Dot(n, w) * std::numbers::inv_pi, LightPdf(ts, p, y - x));
      for (int c = 0; c < kBands; ++c) b[c] += throughput[c] * E[c] * weight;
    }
    x = y;
    const Rgb& rho = ts.MaterialOf(p).reflectance;
    for (int c = 0; c < kBands; ++c) throughput[c] *= rho[c];
  }
  return b;
}

int Run(const std::string& path, int paths, uint64_t seed) {
  auto scene = LoadScene(path, ImportOptions{});
  if (!scene.ok()) return std::fprintf(stderr, "%s\n", scene.status().ToString().c_str()), 1;
  MeshOptions one_per_face;
  one_per_face.follow_contacts = false;
  auto mesh = SubdivideScene(*scene, one_per_face);
  if (!mesh.ok()) return std::fprintf(stderr, "%s\n", mesh.status().ToString().c_str()), 1;
  TraceScene ts{*scene, std::move(*mesh), nullptr, {}, {}, {}, 0};
  auto caster = EmbreeRayCaster::Create(ts.mesh);
  if (!caster.ok()) return std::fprintf(stderr, "%s\n", caster.status().ToString().c_str()), 1;
  ts.caster = std::move(*caster);
  Vec3 lo = ts.mesh.positions[0], hi = lo;
  for (const Vec3& v : ts.mesh.positions) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  ts.epsilon = 1e-6 * Length(hi - lo);
  std::vector<std::vector<uint32_t>> by_object(scene->objects.size() + 1);
  std::vector<double> object_area(by_object.size());
  double power = 0;
  for (uint32_t p = 0; p < ts.mesh.size(); ++p) {
    const uint32_t o =
        std::min<uint32_t>(scene->faces[ts.mesh.patches[p].face].object, scene->objects.size());
    by_object[o].push_back(p);
    object_area[o] += ts.mesh.patches[p].area;
    const Rgb& E = ts.MaterialOf(p).emission;
    if (MaxComponent(E) <= 0) continue;
    ts.emitters.push_back(p);
    power += ts.mesh.patches[p].area * (E[0] + E[1] + E[2]);
    ts.emitter_cdf.push_back(power);
  }
  ts.emitter_pick.assign(ts.mesh.size(), 0.0);
  for (size_t k = 0; k < ts.emitters.size(); ++k) {
    ts.emitter_pick[ts.emitters[k]] =
        (ts.emitter_cdf[k] - (k ? ts.emitter_cdf[k - 1] : 0.0)) / power;
  }
  for (double& c : ts.emitter_cdf) c /= power;
  std::printf("object,area,r,g,b,stderr\n");
  std::vector<std::string> rows(by_object.size());
#pragma omp parallel for schedule(dynamic)
  for (size_t o = 0; o < by_object.size(); ++o) {
    if (by_object[o].empty()) continue;
    std::vector<double> cdf;
    double a = 0;
    Rgb emitted{};  // area x E, summed
    for (uint32_t p : by_object[o]) {
      cdf.push_back(a += ts.mesh.patches[p].area);
      for (int c = 0; c < kBands; ++c)
        emitted[c] += ts.mesh.patches[p].area * ts.MaterialOf(p).emission[c];
    }
    Rng rng(seed * 0x9E3779B97F4A7C15ull + o);
    Rgb sum{};
    double sum2 = 0;
    for (int i = 0; i < paths; ++i) {
      const double u = (i + Uniform(rng)) / paths * a;  // stratified over the object's area
      const size_t k = std::min<size_t>(std::lower_bound(cdf.begin(), cdf.end(), u) - cdf.begin(),
                                        cdf.size() - 1);
      const uint32_t p = by_object[o][k];
      const Rgb b = ReflectedRadiosity(ts, p, PointOn(ts, p, rng), rng);
      for (int c = 0; c < kBands; ++c) sum[c] += b[c];
      const double m = (b[0] + b[1] + b[2]) / 3;
      sum2 += m * m;
    }
    for (int c = 0; c < kBands; ++c) sum[c] += emitted[c] / a * paths;  // exact, no noise
    const double mean =
        (sum[0] + sum[1] + sum[2] - (emitted[0] + emitted[1] + emitted[2]) / a * paths) /
        (3.0 * paths);
    const double se = std::sqrt(std::max(0.0, sum2 / paths - mean * mean) / paths);
    char line[512];
    std::snprintf(line, sizeof line, "%s,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                  o < scene->objects.size() ? scene->objects[o].c_str() : "", a, sum[0] / paths,
                  sum[1] / paths, sum[2] / paths, se);
    rows[o] = line;
  }
  for (const std::string& row : rows) std::fputs(row.c_str(), stdout);
  return 0;
}

}  // namespace
}  // namespace radflux

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: object_reference SCENE PATHS_PER_OBJECT SEED > REF.csv\n");
    return 2;
  }
  return radflux::Run(argv[1], std::atoi(argv[2]), std::strtoull(argv[3], nullptr, 10));
}
