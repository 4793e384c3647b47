#include "solver/formfactor/form_factor_options.h"

namespace radflux {

std::string_view MethodName(FormFactorMethod method) {
  switch (method) {
    case FormFactorMethod::kMonteCarlo:
      return "monte_carlo";
    case FormFactorMethod::kHemicube:
      return "hemicube";
    case FormFactorMethod::kAnalytic:
      return "analytic";
  }
  return "unknown";
}

std::optional<FormFactorMethod> ParseMethod(std::string_view name) {
  for (auto m : {FormFactorMethod::kMonteCarlo, FormFactorMethod::kHemicube,
                 FormFactorMethod::kAnalytic}) {
    if (MethodName(m) == name) return m;
  }
  return std::nullopt;
}

}  // namespace radflux
