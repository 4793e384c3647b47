#include "client/import_flags.h"

#include <cstdio>
#include <cstdlib>

#include "absl/strings/str_cat.h"
#include "solver/scene/mgf_loader.h"

namespace radflux::cli {

void AddImportFlags(CLI::App& app, ImportFlags& f) {
  constexpr const char* kGroup = "Import";
  app.add_option("--max-reflectance", f.max_reflectance,
                 "reflectance at or above 1 in a band is clamped to this")
      ->capture_default_str()
      ->group(kGroup);
  app.add_flag("--strict", f.strict,
               "refuse what the import rules would fix (non-convex, non-planar, zero-area, "
               "duplicate faces, reflectance >= 1), naming file:line")
      ->group(kGroup);
  app.add_flag("--two-sided", f.two_sided,
               "every face is two back-to-back patches, each lit from its own side")
      ->group(kGroup);
  app.add_option("--emit", f.emit,
                 "MATERIAL=R,G,B: make a material an emitter of radiance L_e (repeatable)")
      ->group(kGroup);
  app.add_option("--curve-segments", f.curve_segments,
                 "segments around a full circle of MGF sph, cyl, cone, ring and torus (a sphere "
                 "gets N x ceil(N/2) faces, a cylinder N)")
      ->capture_default_str()
      ->group(kGroup);
}

absl::StatusOr<ImportOptions> ToImportOptions(const ImportFlags& f) {
  ImportOptions options;
  if (!(f.max_reflectance > 0 && f.max_reflectance < 1)) {
    return absl::InvalidArgumentError("--max-reflectance must be in (0, 1)");
  }
  options.max_reflectance = f.max_reflectance;
  const int most = MgfLimits{}.max_curve_segments;
  if (f.curve_segments < 3 || f.curve_segments > most) {
    return absl::InvalidArgumentError(
        absl::StrCat("--curve-segments must be in [3, ", most, "], not ", f.curve_segments));
  }
  options.curve_segments = f.curve_segments;
  options.strict = f.strict;
  options.two_sided = f.two_sided;
  for (const std::string& value : f.emit) {
    absl::StatusOr<std::pair<std::string, Rgb>> emit = ParseEmitRule(value);
    if (!emit.ok()) return emit.status();
    options.emit.push_back(*std::move(emit));
  }
  return options;
}

void PrintImportLog(const ImportLog& log, bool quiet) {
  if (quiet) return;
  for (const std::string& line : log.Lines()) std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace radflux::cli
