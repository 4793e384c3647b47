// Options for building form-factor rows: the method and its accuracy knob.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace radflux {

enum class FormFactorMethod { kMonteCarlo, kHemicube, kAnalytic };

std::string_view MethodName(FormFactorMethod method);
std::optional<FormFactorMethod> ParseMethod(std::string_view name);

struct FormFactorOptions {
  FormFactorMethod method = FormFactorMethod::kMonteCarlo;
  int rays = 64;          // k: monte_carlo rays per patch (default: bench/RESULTS.md, issue 6)
  int hemicube_res = 32;  // r: hemicube top-face resolution (r x r), even
  int samples = 4;        // s: analytic points per patch (also monte_carlo's emitter columns)
  double cutoff = 1e-6;   // entries F_ij below this are dropped (their sum is reported),
                          // except in emitter columns (direct light is never cut)
  uint64_t seed = 1;      // job seed; each patch's samples are seeded from (seed, patch)
  int threads = 0;        // 0 = all cores
  int block_size = 64;    // rows per block: the unit of work, checkpoint and retry
  // monte_carlo: once every row is built (in memory or spilled), average each pair of
  // cosine-ray rows by reciprocity (reciprocal_pairs.h).
  bool reciprocal_pairs = true;
  // monte_carlo: rows and areas of the unknowns' parts not enclosed in a solid (exposed_area.h).
  bool exposed_area = true;
};

// monte_carlo's light samples per s (--samples): a row casts 16 s shadow rays for its emitter
// columns (64 at the default s = 4; more for the few receivers close to an emitter), whatever
// the number of emitter patches.
inline constexpr int kLightSamplesPerS = 16;
// How many of a patch's light samples share one stratified point on it (its cut of the light
// tree and its emitters' set-up): 16 s samples at 4 s points. Fewer points left the spread of
// the light across a patch (a penumbra) under-sampled: on the Cornell box, 16 samples at each
// of 4 points spread the surfaces' means by 0.36% RMS run to run (cosine noise aside, at
// --rays 1024), 4 at each of 16 by 0.23%, at about the same cost.
inline constexpr int kLightSamplesAtAPoint = 4;

// k when the rows' non-emitter entries are Monte Carlo hit counts / k (monte_carlo), else 0:
// what the energy balance needs to know of the rows' sampling noise.
inline int SampledRays(const FormFactorOptions& o) {
  return o.method == FormFactorMethod::kMonteCarlo ? o.rays : 0;
}
// The light samples behind a row's emitter columns, at least (monte_carlo: 16 s), else 0.
inline int LightSamplesPerRow(const FormFactorOptions& o) {
  return o.method == FormFactorMethod::kMonteCarlo ? kLightSamplesPerS * o.samples : 0;
}

}  // namespace radflux
