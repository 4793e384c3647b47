// The import options (solver/scene/import_options.h) as command-line flags, one definition
// for `radflux solve`, `radflux viewfactors` and `radflux submit`: --max-reflectance,
// --strict, --two-sided, --emit MATERIAL=R,G,B (repeatable) and --curve-segments N.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/scene/import_options.h"
#include "solver/scene/import_log.h"

namespace radflux::cli {

struct ImportFlags {
  double max_reflectance = ImportOptions{}.max_reflectance;
  bool strict = false;
  bool two_sided = false;
  std::vector<std::string> emit;  // "MATERIAL=R,G,B", as typed
  int curve_segments = ImportOptions{}.curve_segments;
};

// Adds the flags to `app`, in the help group "Import".
void AddImportFlags(CLI::App& app, ImportFlags& flags);

// The options the flags say. INVALID_ARGUMENT naming the --emit value that is not
// NAME=R,G,B with three finite numbers >= 0, a --max-reflectance outside (0, 1), or a
// --curve-segments outside [3, MgfLimits::max_curve_segments].
absl::StatusOr<ImportOptions> ToImportOptions(const ImportFlags& flags);

// Prints the import log's lines (one per kind of fix-up) on stderr unless `quiet`.
void PrintImportLog(const ImportLog& log, bool quiet);

}  // namespace radflux::cli
