#include "solver/formfactor/direct_lit.h"

#include <memory>

#include "solver/core/parallel.h"
#include "solver/formfactor/bright_reflectors.h"
#include "solver/formfactor/light_sampling.h"
#include "solver/formfactor/row_context.h"
#include "solver/mesh/patch_attributes.h"

namespace radflux {
namespace {

constexpr uint64_t kProbeSeed = 0x6c69742070726f62;  // fixed: not the job's seed

double BandSum(const Rgb& v) {
  double s = 0;
  for (int k = 0; k < kBands; ++k) s += v[k];
  return s;
}

}  // namespace

std::vector<DirectLight> ProbeDirectLight(const Scene& scene, const PatchMesh& mesh,
                                          const RayCaster& caster) {
  std::vector<DirectLight> out(mesh.size(), DirectLight::kUnlit);
  const PatchAttributes attributes = ComputePatchAttributes(scene, mesh);
  const RowContext context = MakeRowContext(mesh, attributes, caster);
  const LightSampler lights(context);
  if (lights.empty()) return out;
  double power = 0, area = 0;  // emitted, summed over bands; the patches' area
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    power += attributes.area[p] * BandSum(attributes.emission[p]);
    area += attributes.area[p];
  }
  const double bright = kBrightReflector * power / area;
  std::vector<std::unique_ptr<RowAccumulator>> rows(static_cast<size_t>(DefaultThreadCount()));
  ParallelFor(static_cast<int64_t>(mesh.size()), 256, 0, [&](int64_t begin, int64_t end) {
    std::unique_ptr<RowAccumulator>& row = rows[static_cast<size_t>(ThreadIndex())];
    if (row == nullptr) row = std::make_unique<RowAccumulator>(mesh.size());
    for (int64_t p = begin; p < end; ++p) {
      if (mesh.patches[p].hidden || BandSum(attributes.emission[p]) > 0) continue;
      lights.AddEmitterColumns(static_cast<uint32_t>(p), kLitProbePoints, 1, kProbeSeed, *row);
      bool lit = false;
      Rgb direct{};  // D = sum_j F_pj E_j
      for (uint32_t j : row->Touched()) {
        lit = lit || row->Value(j) > 0;
        for (int k = 0; k < kBands; ++k) direct[k] += row->Value(j) * attributes.emission[j][k];
      }
      row->Clear();
      double reflected = 0;
      for (int k = 0; k < kBands; ++k) reflected += attributes.reflectance[p][k] * direct[k];
      out[p] = !lit ? DirectLight::kUnlit
                    : (reflected > bright &&
                               reflected * attributes.area[p] >= kBrightReflectorPower * power
                           ? DirectLight::kBright
                           : DirectLight::kLit);
    }
  });
  return out;
}

}  // namespace radflux
