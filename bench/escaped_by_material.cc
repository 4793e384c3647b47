// escaped_by_material [--emit MATERIAL=R,G,B ...] SCENE SEED [PATCHES]
// Where radflux's rows lose light, per material: the job `radflux solve SCENE --seed SEED
// [--patches PATCHES]` runs (2,000 unknowns unless given, the solver auto, the rest
// JobOptions' defaults), and for each unknown with a row the power its row brings
// nowhere, A_i B_i (1 - sum_j F_ij) (energy_balance.h's escaped), summed by the material of the
// unknown's first patch, as a share of the emitted power (mean over bands). Beside
// bench/light_losses' per-material table it shows which surfaces' rows lose more light than
// the scene does.
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench/reference_paths.h"
#include "solver/pipeline.h"
#include "solver/scene/load_scene.h"
#include "solver/sparse/row_store.h"

int main(int argc, char** argv) {
  radflux::ImportOptions import;
  const int first = radflux::TakeEmitFlags(argc, argv, import);
  if (first < 0) return 2;
  if (argc - first != 2 && argc - first != 3) {
    std::fprintf(stderr,
                 "usage: escaped_by_material [--emit MATERIAL=R,G,B ...] SCENE SEED [PATCHES]\n");
    return 2;
  }
  auto scene = radflux::LoadScene(argv[first], import);
  if (!scene.ok()) return std::fprintf(stderr, "%s\n", scene.status().ToString().c_str()), 1;
  const radflux::Scene copy = *scene;
  radflux::JobOptions options;
  options.mesh.target_patches = argc - first == 3 ? std::atol(argv[first + 2]) : 2000;
  options.solver.method = radflux::SolverMethod::kAuto;
  options.form_factors.seed = std::strtoull(argv[first + 1], nullptr, 10);
  auto result = radflux::RunJob(*std::move(scene), options, {});
  if (!result.ok()) return std::fprintf(stderr, "%s\n", result.status().ToString().c_str()), 1;
  const radflux::RadiositySystem system = result->System();
  const radflux::PatchAttributes& p = *system.patches;
  const radflux::PatchClusters& clusters = result->job->clusters;
  const std::vector<radflux::Rgb>& b =
      clusters.empty() ? result->solve.radiosity : result->unknown_radiosity;
  std::vector<double> lost(copy.materials.size(), 0.0);
  double emitted = 0, total = 0, first_flight = 0, reflected_by_emitters = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    for (int c = 0; c < radflux::kBands; ++c) emitted += p.area[i] * p.emission[i][c] / 3;
  }
  const absl::Status read = radflux::ForEachRows(
      system.form_factors, system.row_store, [&](const radflux::RowsView& rows) {
        for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
          if (radflux::MaxComponent(p.reflectance[i]) <= 0) continue;
          double sum = 0;
          for (float v : rows.RowValues(i)) sum += v;
          const uint32_t patch = clusters.empty() ? i : clusters.Members(i)[0];
          const uint32_t material = copy.faces[result->job->mesh.patches[patch].face].material;
          const double out = p.area[i] * (b[i][0] + b[i][1] + b[i][2]) / 3 * (1 - sum);
          lost[material] += out;
          total += out;
          if (radflux::MaxComponent(p.emission[i]) > 0) {
            for (int c = 0; c < radflux::kBands; ++c) {
              reflected_by_emitters += p.area[i] * (b[i][c] - p.emission[i][c]) / 3;
            }
          }
          first_flight += p.area[i] * (p.emission[i][0] + p.emission[i][1] + p.emission[i][2]) /
                          3 * (1 - sum);
        }
      });
  if (!read.ok()) return std::fprintf(stderr, "%s\n", read.ToString().c_str()), 1;
  std::printf("total,%.5f\nfirst_flight,%.5f\nreflected_by_emitters,%.5f\nmaterial,lost\n",
              total / emitted, first_flight / emitted, reflected_by_emitters / emitted);
  for (size_t m = 0; m < lost.size(); ++m) {
    if (lost[m] != 0) std::printf("%s,%.5f\n", copy.materials[m].name.c_str(), lost[m] / emitted);
  }
  return 0;
}
