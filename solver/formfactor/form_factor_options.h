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
  int rays = 64;           // k: monte_carlo rays per patch (default: bench/RESULTS.md, issue 6)
  int hemicube_res = 32;   // r: hemicube top-face resolution (r x r), even
  int samples = 4;         // s: analytic points per patch (also monte_carlo's emitter columns)
  double cutoff = 1e-6;    // entries F_ij below this are dropped (their sum is reported)
  uint64_t seed = 1;       // job seed; each patch's samples are seeded from (seed, patch)
  int threads = 0;         // 0 = all cores
  int block_size = 64;     // rows per block: the unit of work, checkpoint and retry
};

}  // namespace radflux
