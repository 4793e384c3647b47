// The options of `radflux viewfactors` as command-line flags, one definition for that
// command and for `radflux submit --viewfactors` (the same spelling, a contract scripts use):
// --by, --format, --min-vf, --integration, the adaptive knobs (--vf-tolerance,
// --far-ratio, --middle-ratio, --memory-limit), and the files (-o/--output, --svf).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "solver/formfactor/view_factor_job.h"

namespace radflux::cli {

struct ViewFactorFlags {
  std::string by = "object", format = "csv", integration = "auto";
  std::string output, svf;  // the view-factor file and the sky-view-factor file ("" = none)
  double min_vf = 0;
  PairIntegration pairs;
  uint64_t memory_limit = 0;
};

// Adds the flags to `app` in the help group kViewFactorGroup; -o/--output is required when
// `output_required`.
void AddViewFactorFlags(CLI::App& app, ViewFactorFlags& flags, bool output_required);
inline constexpr const char* kViewFactorGroup = "View factors";

// The long names ("--by") of the options given on `app`'s command line, in any group.
std::vector<std::string> GivenFlagNames(const CLI::App& app);

// The integration the flags ask for (kAuto: decided by the model, see view_factor_flags.h).
ViewFactorIntegration RequestedIntegration(const ViewFactorFlags& flags);

// The job options the flags say, with `job` (meshing and form factors) beside them. The
// enclosure adjustment is the model's to say (LoadViewFactorScene).
ViewFactorJobOptions ToViewFactorJobOptions(const ViewFactorFlags& flags, const JobOptions& job);

}  // namespace radflux::cli
