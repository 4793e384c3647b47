#include "solver/formfactor/cell_direct.h"

#include <algorithm>
#include <chrono>

#include "solver/core/parallel.h"
#include "solver/formfactor/cell_columns.h"
#include "solver/formfactor/light_sampling.h"

namespace radflux {
namespace {

// D_c per cell (zero for cells not sampled: `sampled` 0), from the columns the rows kept
// (context.cell_columns) or else drawn again and kept there, so that a second pass over the
// same cells (the cells' detail, then the push-down) draws none twice; counts the cells found
// kept into `kept` and returns the shadow rays cast.
uint64_t SampleCellDirect(const RowContext& context, const std::vector<uint8_t>& sampled,
                          const std::vector<Rgb>& b, const FormFactorOptions& options,
                          std::vector<Rgb>& direct, uint64_t& kept) {
  const LightSampler lights(context);
  const int threads = options.threads > 0 ? options.threads : DefaultThreadCount();
  const int budget = CellLightSamplesPerGroup(options);
  const size_t slots = static_cast<size_t>(std::max(threads, DefaultThreadCount()));
  std::vector<uint64_t> rays(slots, 0), found(slots, 0);
  direct.assign(sampled.size(), Rgb{});
  ParallelFor(static_cast<int64_t>(sampled.size()), 64, threads, [&](int64_t begin, int64_t end) {
    const size_t t = static_cast<size_t>(ThreadIndex());
    thread_local std::vector<CellColumn> drawn;
    for (int64_t c = begin; c < end; ++c) {
      if (!sampled[c]) continue;
      const uint32_t cell = static_cast<uint32_t>(c);
      const std::vector<CellColumn>* columns =
          context.cell_columns != nullptr ? context.cell_columns->Find(cell, options.seed, budget)
                                          : nullptr;
      if (columns != nullptr) {
        ++found[t];
      } else {
        rays[t] += lights.CellEmitterColumns(cell, budget, options.seed, drawn);
        if (context.cell_columns != nullptr) {
          context.cell_columns->Keep(cell, options.seed, budget, drawn);
        }
        columns = &drawn;
      }
      Rgb& d = direct[c];
      for (const CellColumn& column : *columns) {
        for (int k = 0; k < kBands; ++k) d[k] += column.form_factor * b[column.emitter][k];
      }
    }
  });
  uint64_t total = 0;
  for (size_t t = 0; t < slots; ++t) total += rays[t], kept += found[t];
  return total;
}

}  // namespace

CellDirectLight ComputeCellDirectLight(const RowContext& context, const std::vector<Rgb>& b,
                                       const FormFactorOptions& options) {
  CellDirectLight light;
  const PatchClusters& cells = *context.cells;
  const uint32_t unknowns = context.Unknowns();
  light.group.resize(cells.size());
  light.sampled.resize(cells.size());
  for (uint32_t c = 0; c < cells.size(); ++c) {
    const uint32_t g = light.group[c] = context.UnknownOf(cells.Members(c)[0]);
    light.sampled[c] = context.CellsOf(g).size() > 1 && context.needs_row[g];
    light.cells += light.sampled[c];
  }
  light.rays = SampleCellDirect(context, light.sampled, b, options, light.direct, light.kept);
  light.mean.assign(unknowns, Rgb{});
  for (uint32_t c = 0; c < cells.size(); ++c) {
    for (int k = 0; k < kBands; ++k)
      light.mean[light.group[c]][k] += cells.area[c] * light.direct[c][k];
  }
  for (uint32_t g = 0; g < unknowns; ++g) {
    for (int k = 0; k < kBands; ++k) light.mean[g][k] /= context.Area(g);
  }
  // Light samples from a group's enclosed part found nothing (exposed_area.h): the mean is
  // its exposed part's, as the group's B is (its row was scaled so). A cell keeps its own
  // light: an exposed cell's is right as it is, an enclosed one's is no one's to see.
  for (uint32_t g = 0; g < unknowns; ++g) {
    for (double& d : light.mean[g]) d /= context.Exposure(g);
  }
  return light;
}

std::vector<Rgb> CellDeviation(const CellDirectLight& light, const PatchAttributes& attributes) {
  std::vector<Rgb> deviation(light.direct.size(), Rgb{});
  for (uint32_t c = 0; c < deviation.size(); ++c) {
    if (!light.sampled[c]) continue;
    const uint32_t g = light.group[c];
    for (int k = 0; k < kBands; ++k) {
      deviation[c][k] = attributes.reflectance[g][k] * (light.direct[c][k] - light.mean[g][k]);
    }
  }
  return deviation;
}

CellDirectResult PushDownWithCellDirect(const RowContext& context,
                                        const PatchAttributes& attributes,
                                        const std::vector<Rgb>& b, const FormFactorOptions& options,
                                        std::span<const Rgb> indirect) {
  const auto start = std::chrono::steady_clock::now();
  CellDirectResult result;
  if (context.cells == nullptr) {
    result.radiosity = PushDownToPatches(*context.clusters, b);
    return result;
  }
  const PatchClusters& cells = *context.cells;
  const CellDirectLight light = ComputeCellDirectLight(context, b, options);
  result.cells = light.cells;
  result.kept = light.kept;
  result.rays = light.rays;
  const std::vector<Rgb> deviation = CellDeviation(light, attributes);
  result.radiosity.resize(cells.of_patch.size());
  for (uint32_t p = 0; p < result.radiosity.size(); ++p) {
    const uint32_t c = cells.of_patch[p], g = light.group[c];
    Rgb& out = result.radiosity[p];
    out = b[g];
    if (!light.sampled[c]) continue;
    bool lifted = false;
    for (int k = 0; k < kBands; ++k) {
      out[k] += deviation[c][k] + (indirect.empty() ? 0.0 : indirect[c][k]);
      lifted = lifted || out[k] < attributes.emission[g][k];
      out[k] = std::max(out[k], attributes.emission[g][k]);
    }
    result.lifted += lifted;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace radflux
