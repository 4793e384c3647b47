// compare_patch_values A.csv REFERENCE.csv: error of one run's per-patch radiosity
// against a reference on the same mesh: area-weighted relative RMS and max relative
// error per band, printed as one line of JSON. The max skips patches whose reference B
// is below 1% of the band's area-weighted mean (e.g. floor under a block, B ~ 0), where
// a relative error says nothing.
#include <cmath>
#include <cstdio>

#include "solver/output/patch_values_csv.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: compare_patch_values RUN.csv REFERENCE.csv\n");
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
  std::printf("{\"patches\": %zu", run->size());
  for (int b = 0; b < 3; ++b) {
    double err2 = 0, ref2 = 0, worst = 0, sum = 0, area = 0;
    for (const auto& v : *ref) {
      sum += v.area * v.radiosity[b];
      area += v.area;
    }
    const double floor = 0.01 * sum / area;
    for (size_t p = 0; p < run->size(); ++p) {
      const double a = (*ref)[p].area, x = (*run)[p].radiosity[b], r = (*ref)[p].radiosity[b];
      err2 += a * (x - r) * (x - r);
      ref2 += a * r * r;
      if (r > floor) worst = std::max(worst, std::abs(x - r) / r);
    }
    std::printf(", \"rms_%c\": %.6g, \"max_%c\": %.6g", "rgb"[b], std::sqrt(err2 / ref2), "rgb"[b],
                worst);
  }
  std::printf("}\n");
  return 0;
}
