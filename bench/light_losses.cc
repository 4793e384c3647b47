// light_losses [--emit MATERIAL=R,G,B ...] SCENE PARTICLES SEED
// Where a scene's emitted light ends when no front side takes it in, by particle tracing
// under radflux's conventions (bench/reference_paths: nothing of the radiosity solver): per
// band, the share of the emitted power lost on back sides or in the void, and of it the
// share lost on flights that leave an emitter's face; then, per material, the share (mean
// over bands) lost on flights that leave its faces (bench/escaped_by_material gives
// radflux's rows' count of the same). radflux's report books the same light
// as energy_balance.escaped (its rows' missing sums): the two agree when the rows lose no
// more than the scene does (issue 21: the conference room's rows lost 17.7% against 14.6%
// here until rays from enclosed parts of surfaces stopped counting, exposed_area.h).
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/reference_paths.h"
#include "solver/scene/import_options.h"
#include "solver/scene/load_scene.h"

int main(int argc, char** argv) {
  radflux::ImportOptions import;
  const int first = radflux::TakeEmitFlags(argc, argv, import);
  if (first < 0) return 2;
  if (argc - first != 3) {
    std::fprintf(stderr, "usage: light_losses [--emit MATERIAL=R,G,B ...] SCENE PARTICLES SEED\n");
    return 2;
  }
  auto scene = radflux::LoadScene(argv[first], import);
  if (!scene.ok()) return std::fprintf(stderr, "%s\n", scene.status().ToString().c_str()), 1;
  auto tracer = radflux::ReferenceTracer::Create(*scene);
  if (!tracer.ok()) return std::fprintf(stderr, "%s\n", tracer.status().ToString().c_str()), 1;
  const long particles = std::atol(argv[first + 1]);
  const uint64_t seed = std::strtoull(argv[first + 2], nullptr, 10);
  std::vector<radflux::ReferenceTracer::Loss> per_thread(
      static_cast<size_t>(omp_get_max_threads()));
  std::vector<std::vector<double>> per_material(per_thread.size());
#pragma omp parallel
  {
    const int t = omp_get_thread_num();
    radflux::ReferenceRng rng(seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(t));
    radflux::ReferenceTracer::Loss& mine = per_thread[static_cast<size_t>(t)];
    std::vector<double>& by_material = per_material[static_cast<size_t>(t)];
    by_material.assign(scene->materials.size(), 0.0);
#pragma omp for schedule(static)
    for (long i = 0; i < particles; ++i) {
      const radflux::ReferenceTracer::Loss one = (*tracer)->TraceLoss(rng);
      for (int c = 0; c < radflux::kBands; ++c) {
        mine.emitted[c] += one.emitted[c];
        mine.lost[c] += one.lost[c];
        mine.lost_leaving_emitters[c] += one.lost_leaving_emitters[c];
        mine.lost_first_flight[c] += one.lost_first_flight[c];
        mine.reflected_by_emitters[c] += one.reflected_by_emitters[c];
      }
      if (one.from_patch != radflux::kNoPatch) {
        const radflux::PatchMesh& mesh = (*tracer)->mesh();
        by_material[scene->faces[mesh.patches[one.from_patch].face].material] +=
            (one.lost[0] + one.lost[1] + one.lost[2]) / 3;
      }
    }
  }
  radflux::ReferenceTracer::Loss total;
  for (const auto& t : per_thread) {
    for (int c = 0; c < radflux::kBands; ++c) {
      total.emitted[c] += t.emitted[c];
      total.lost[c] += t.lost[c];
      total.lost_leaving_emitters[c] += t.lost_leaving_emitters[c];
      total.lost_first_flight[c] += t.lost_first_flight[c];
      total.reflected_by_emitters[c] += t.reflected_by_emitters[c];
    }
  }
  std::printf("band,lost,lost_leaving_emitters,lost_first_flight,reflected_by_emitters\n");
  for (int c = 0; c < radflux::kBands; ++c) {
    std::printf("%d,%.5f,%.5f,%.5f,%.5f\n", c, total.lost[c] / total.emitted[c],
                total.lost_leaving_emitters[c] / total.emitted[c],
                total.lost_first_flight[c] / total.emitted[c],
                total.reflected_by_emitters[c] / total.emitted[c]);
  }
  std::printf("material,lost\n");
  for (size_t m = 0; m < scene->materials.size(); ++m) {
    double lost = 0;
    for (const auto& t : per_material) lost += t[m];
    if (lost > 0) std::printf("%s,%.5f\n", scene->materials[m].name.c_str(), lost / particles);
  }
  return 0;
}
