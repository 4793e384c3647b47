#include "solver/formfactor/view_factor_flags.h"

#include <algorithm>

#include "solver/formfactor/view_factor_scene.h"

namespace radflux {
namespace {

bool Given(std::span<const std::string> given, std::span<const char* const> flags,
           std::string& which) {
  for (const char* flag : flags) {
    if (std::find(given.begin(), given.end(), flag) != given.end()) {
      which = flag;
      return true;
    }
  }
  return false;
}

bool FormFactorsGiven(std::span<const std::string> given) {
  return std::find(given.begin(), given.end(), "--form-factors") != given.end();
}

}  // namespace

ViewFactorIntegration ResolveViewFactorIntegration(ViewFactorIntegration requested,
                                                   std::span<const std::string> given,
                                                   const Scene& scene, SurfaceGrouping by) {
  if (requested != ViewFactorIntegration::kAuto) return requested;
  if (FormFactorsGiven(given)) return ViewFactorIntegration::kPatches;
  return EverySurfaceIsOneFace(scene, by) ? ViewFactorIntegration::kAdaptive
                                          : ViewFactorIntegration::kPatches;
}

absl::Status CheckViewFactorFlags(std::span<const std::string> given,
                                  const std::string& model_path,
                                  ViewFactorIntegration requested,
                                  ViewFactorIntegration resolved) {
  std::string flag;
  if (Given(given, kViewFactorSolverOnlyFlags, flag)) {
    return absl::InvalidArgumentError(
        flag + " is for radflux solve only; view factors are geometry only (no emitter, no solver)");
  }
  if (IsRawViewFactorModel(model_path) && Given(given, kViewFactorImportFlags, flag)) {
    return absl::InvalidArgumentError(flag + " is an import rule; .stl and .vs3 files are read "
                                             "as they are (surface k = facet or record k)");
  }
  if (resolved == ViewFactorIntegration::kAdaptive && Given(given, kViewFactorPatchFlags, flag)) {
    return absl::InvalidArgumentError(
        flag + " applies to --integration patches; this run integrates per surface pair "
               "(adaptive: every surface is one face)");
  }
  if (resolved == ViewFactorIntegration::kPatches && Given(given, kViewFactorAdaptiveFlags, flag)) {
    return absl::InvalidArgumentError(
        flag + " applies to adaptive integration; this run uses patch rows (" +
        (requested == ViewFactorIntegration::kPatches ? "--integration patches"
         : FormFactorsGiven(given)                    ? "--form-factors given"
                                                      : "a surface with several faces: try --by face") +
        ")");
  }
  return absl::OkStatus();
}

}  // namespace radflux
