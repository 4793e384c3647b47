// compare_patch_values RUN.csv REFERENCE.csv [SCENE.obj]: error of one run's per-patch
// radiosity against a reference on the same mesh, as one line of JSON:
// - rms_*: area-weighted relative RMS of B per band over the patches that do not emit
//   (with SCENE given; emitters' B is mostly their own E and would dilute the error);
// - max_*: the largest relative error per band, over patches whose reference B is at
//   least 1% of the band's mean (below that, e.g. under a block, it says nothing);
// - surfaces_rms: with SCENE, the RMS over the scene's groups ('g' names) of the
//   relative error of each group's area-weighted mean radiance (issue 6's measure).
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "solver/output/patch_values_csv.h"
#include "solver/scene/obj_loader.h"

namespace {

using radflux::PatchValue;

struct Compared {
  double rms = 0, max = 0;
};

Compared CompareBand(const std::vector<PatchValue>& run, const std::vector<PatchValue>& ref,
                     const std::vector<bool>& skip, int b) {
  double err2 = 0, ref2 = 0, sum = 0, area = 0;
  for (size_t p = 0; p < ref.size(); ++p) {
    if (skip[p]) continue;
    sum += ref[p].area * ref[p].radiosity[b];
    area += ref[p].area;
  }
  Compared out;
  for (size_t p = 0; p < ref.size(); ++p) {
    if (skip[p]) continue;
    const double a = ref[p].area, x = run[p].radiosity[b], r = ref[p].radiosity[b];
    err2 += a * (x - r) * (x - r);
    ref2 += a * r * r;
    if (r > 0.01 * sum / area) out.max = std::max(out.max, std::abs(x - r) / r);
  }
  out.rms = ref2 > 0 ? std::sqrt(err2 / ref2) : 0;
  return out;
}

// RMS over groups and bands of the relative error of each group's mean radiosity.
double SurfacesRms(const std::vector<PatchValue>& run, const std::vector<PatchValue>& ref,
                   const radflux::Scene& scene, const std::vector<bool>& skip) {
  std::map<std::string, std::array<double, 7>> groups;  // area, run rgb, ref rgb
  for (size_t p = 0; p < ref.size(); ++p) {
    if (skip[p]) continue;
    auto& g = groups[scene.groups[scene.faces[ref[p].face].group]];
    g[0] += ref[p].area;
    for (int b = 0; b < 3; ++b) {
      g[1 + b] += ref[p].area * run[p].radiosity[b];
      g[4 + b] += ref[p].area * ref[p].radiosity[b];
    }
  }
  double sum2 = 0;
  int count = 0;
  for (const auto& [name, g] : groups) {
    for (int b = 0; b < 3; ++b) {
      if (g[4 + b] <= 0) continue;
      const double e = (g[1 + b] - g[4 + b]) / g[4 + b];
      sum2 += e * e;
      ++count;
    }
  }
  return count ? std::sqrt(sum2 / count) : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: compare_patch_values RUN.csv REFERENCE.csv [SCENE.obj]\n");
    return 2;
  }
  auto run = radflux::ReadPatchValuesCsv(argv[1]);
  auto ref = radflux::ReadPatchValuesCsv(argv[2]);
  if (!run.ok() || !ref.ok() || run->size() != ref->size()) {
    std::fprintf(stderr, "compare_patch_values: cannot compare (%s / %s / sizes differ)\n",
                 std::string(run.status().message()).c_str(),
                 std::string(ref.status().message()).c_str());
    return 1;
  }
  std::vector<bool> skip(ref->size(), false);
  absl::StatusOr<radflux::Scene> scene = absl::NotFoundError("no scene given");
  if (argc == 4) {
    scene = radflux::LoadObjFile(argv[3]);
    if (!scene.ok()) {
      std::fprintf(stderr, "compare_patch_values: %s\n", std::string(scene.status().message()).c_str());
      return 1;
    }
    for (size_t p = 0; p < ref->size(); ++p) {
      skip[p] = scene->materials[scene->faces[(*ref)[p].face].material].IsEmitter();
    }
  }
  std::printf("{\"patches\": %zu", run->size());
  for (int b = 0; b < 3; ++b) {
    const Compared c = CompareBand(*run, *ref, skip, b);
    std::printf(", \"rms_%c\": %.6g, \"max_%c\": %.6g", "rgb"[b], c.rms, "rgb"[b], c.max);
  }
  if (scene.ok()) std::printf(", \"surfaces_rms\": %.6g", SurfacesRms(*run, *ref, *scene, skip));
  std::printf("}\n");
  return 0;
}
