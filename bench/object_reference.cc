// object_reference [--emit MATERIAL=R,G,B ...] SCENE MAX_PATHS SEED [RELATIVE_ERROR [OBJECT,...]]
// > REF.csv: an independent per-object reference for a scene's mean radiosity, by path tracing,
// for bench/real_scenes.py (issue 21); --emit makes a material an emitter, as radflux's does. With
// a comma-separated list of object names, only those objects' rows (the classroom's five largest
// surfaces at 4M paths each: ~2 CPU-min, standard error 0.3-0.4%).
//
// Nothing of the radiosity solver is used (bench/reference_paths.h says what is): per object,
// its area mean of E exactly, plus the mean of rho(x) H(x) over points x uniform by area over
// its faces, in batches of kBatch paths at randomly shifted Hammersley points over the
// object's area (stratified in two dimensions). Batches are added until the mean's standard
// error, from the spread of the batch means (so the stratification is credited), is at most
// RELATIVE_ERROR (default 0.001) of the mean, with at least kMinBatches and at most MAX_PATHS
// paths: objects that need more paths get more. Before that, kGuideParticles particles from
// the emitters find each patch's reflected power, the paths' guide. Objects run in parallel
// (OpenMP). Checked (bench/object_reference_check.py): a closed box of E = pi, rho = 0.5 gives
// 2 pi on every wall; lit by its floor only, sum A B = 2 pi.
// Output rows: object,area,r,g,b,stderr,paths (area-weighted mean B per band, W/m^2 per band;
// the standard error of (r+g+b)/3; the paths traced).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/reference_paths.h"
#include "solver/scene/import_options.h"
#include "solver/scene/load_scene.h"

namespace radflux {
namespace {

constexpr int kBatch = 1024;
constexpr int kMinBatches = 8;
constexpr int kGuideParticles = 1 << 20;

double Uniform(ReferenceRng& rng) { return std::uniform_real_distribution<double>(0, 1)(rng); }

// Van der Corput's radical inverse of i in base 2, in [0, 1).
double RadicalInverse2(uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return i * 0x1p-32;
}

// One object's row: its patches, their area running sum; batches until the error is met.
std::string ObjectRow(const ReferenceTracer& tracer, const std::string& name,
                      const std::vector<uint32_t>& patches, int max_paths, double relative,
                      ReferenceRng& rng) {
  std::vector<double> cdf;
  double a = 0;
  Rgb emitted{};  // area x E, summed
  for (uint32_t p : patches) {
    const double area = tracer.mesh().patches[p].area;
    cdf.push_back(a += area);
    for (int c = 0; c < kBands; ++c) emitted[c] += area * tracer.MaterialOf(p).emission[c];
  }
  Rgb sum{};
  double batch_sum = 0, batch_sum2 = 0, se = 0;
  int batches = 0;
  while (batches * kBatch < max_paths) {
    double batch = 0;
    const double shift_x = Uniform(rng), shift_y = Uniform(rng);
    for (int i = 0; i < kBatch; ++i) {
      // Hammersley's points, shifted at random per batch: stratified in two dimensions over
      // the object (the first picks the face by area and where along it; the second across).
      const double ux = std::fmod((i + 0.5) / kBatch + shift_x, 1.0);
      const double uy = std::fmod(RadicalInverse2(static_cast<uint32_t>(i)) + shift_y, 1.0);
      const size_t k = std::min<size_t>(
          std::upper_bound(cdf.begin(), cdf.end(), ux * a) - cdf.begin(), cdf.size() - 1);
      const uint32_t p = patches[k];
      const double below = k ? cdf[k - 1] : 0.0;
      const double along = std::clamp((ux * a - below) / (cdf[k] - below), 0.0, 1.0 - 1e-12);
      const PatchPointSampler sample(tracer.mesh(), p);
      const Rgb b = tracer.ReflectedRadiosity(p, sample({along, uy}), rng);
      for (int c = 0; c < kBands; ++c) sum[c] += b[c];
      batch += (b[0] + b[1] + b[2]) / (3.0 * kBatch);
    }
    ++batches;
    batch_sum += batch;
    batch_sum2 += batch * batch;
    const double mean = batch_sum / batches;
    // The batch means' sample variance over the batches, for their mean.
    se = batches > 1 ? std::sqrt(std::max(0.0, batch_sum2 / batches - mean * mean) / (batches - 1))
                     : 0.0;
    const double b = mean + (emitted[0] + emitted[1] + emitted[2]) / (3 * a);
    if (batches >= kMinBatches && se <= relative * b) break;
  }
  const int paths = batches * kBatch;
  char line[512];
  std::snprintf(line, sizeof line, "%s,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n", name.c_str(), a,
                sum[0] / paths + emitted[0] / a, sum[1] / paths + emitted[1] / a,
                sum[2] / paths + emitted[2] / a, se, paths);
  return line;
}

int Run(const ImportOptions& import, const std::string& path, int max_paths, uint64_t seed,
        double relative, const std::string& only) {
  auto scene = LoadScene(path, import);
  if (!scene.ok()) return std::fprintf(stderr, "%s\n", scene.status().ToString().c_str()), 1;
  auto tracer = ReferenceTracer::Create(*scene);
  if (!tracer.ok()) return std::fprintf(stderr, "%s\n", tracer.status().ToString().c_str()), 1;
  (*tracer)->SetGuide(ParticleGuide(**tracer, seed, kGuideParticles));
  const PatchMesh& mesh = (*tracer)->mesh();
  std::vector<std::vector<uint32_t>> by_object(scene->objects.size() + 1);
  for (uint32_t p = 0; p < mesh.size(); ++p)
    by_object[std::min<size_t>(scene->faces[mesh.patches[p].face].object, scene->objects.size())]
        .push_back(p);
  std::vector<std::string> rows(by_object.size());
#pragma omp parallel for schedule(dynamic)
  for (size_t o = 0; o < by_object.size(); ++o) {
    if (by_object[o].empty()) continue;
    if (!only.empty() &&
        (o == scene->objects.size() ||
         ("," + only + ",").find("," + scene->objects[o] + ",") == std::string::npos))
      continue;
    ReferenceRng rng(seed * 0x9E3779B97F4A7C15ull + o);
    rows[o] = ObjectRow(**tracer, o < scene->objects.size() ? scene->objects[o] : "", by_object[o],
                        max_paths, relative, rng);
  }
  std::printf("object,area,r,g,b,stderr,paths\n");
  for (const std::string& row : rows) std::fputs(row.c_str(), stdout);
  return 0;
}

}  // namespace
}  // namespace radflux

int main(int argc, char** argv) {
  radflux::ImportOptions import;
  const int first = radflux::TakeEmitFlags(argc, argv, import);
  if (first < 0) return 2;
  const int positional = argc - first;
  if (positional < 3 || positional > 5) {
    std::fprintf(stderr,
                 "usage: object_reference [--emit MATERIAL=R,G,B ...] SCENE MAX_PATHS_PER_OBJECT "
                 "SEED [RELATIVE_ERROR [OBJECT,...]] > REF.csv\n");
    return 2;
  }
  char** arg = argv + first;
  return radflux::Run(import, arg[0], std::atoi(arg[1]), std::strtoull(arg[2], nullptr, 10),
                      positional >= 4 ? std::atof(arg[3]) : 1e-3, positional == 5 ? arg[4] : "");
}
