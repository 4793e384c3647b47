#include "client/viewfactors_flags.h"

namespace radflux::cli {

void AddViewFactorFlags(CLI::App& app, ViewFactorFlags& f, bool output_required) {
  for (CLI::Option* option : {
           app.add_option("--by", f.by, "what a surface is")
               ->check(CLI::IsMember({"object", "group", "face"}))
               ->capture_default_str(),
           app.add_option("-o,--output", f.output, "view-factor file to write")
               ->required(output_required),
           app.add_option("--format", f.format,
                          "csv (dense, named), sparse (i j F dropped; uDALES vfsparse.inp), "
                          "view3d (View3D's text output)")
               ->check(CLI::IsMember({"csv", "sparse", "view3d"}))
               ->capture_default_str(),
           app.add_option("--min-vf", f.min_vf,
                          "sparse: leave out F below this; each line's 4th column is its row's "
                          "dropped sum")
               ->check(CLI::Range(0.0, 1.0)),
           app.add_option("--svf", f.svf,
                          "also write sky view factors 1 - sum_j F_ij, one per line"),
           app.add_option("--integration", f.integration,
                          "auto (adaptive when every surface is one face and --form-factors is "
                          "not given), adaptive (per surface pair: exact inner integral, one "
                          "point when far, refined where the estimate moves, visibility only "
                          "where the shaft holds geometry) or patches (form-factor rows of the "
                          "patch mesh)")
               ->check(CLI::IsMember({"auto", "adaptive", "patches"}))
               ->capture_default_str(),
           app.add_option("--vf-tolerance", f.pairs.tolerance,
                          "adaptive: relative change below which a triangle is not refined")
               ->check(CLI::Range(1e-9, 1.0))
               ->capture_default_str(),
           app.add_option("--far-ratio", f.pairs.far_ratio,
                          "adaptive: one point when distance / the surface's diameter is at "
                          "least this")
               ->check(CLI::Range(0.0, 1e9))
               ->capture_default_str(),
           app.add_option("--middle-ratio", f.pairs.middle_ratio,
                          "adaptive: 2 x 2 Gauss points (no refinement) when distance / the "
                          "surface's diameter is at least this and below --far-ratio")
               ->check(CLI::Range(0.0, 1e9))
               ->capture_default_str(),
           app.add_option("--memory-limit", f.memory_limit,
                          "adaptive: at most this many bytes of rows in flight (e.g. 64M; "
                          "default a quarter of physical memory): when the triangle of pairs "
                          "fits, each pair is computed once, else rows are computed and "
                          "written one block at a time")
               ->transform(CLI::AsSizeValue(false)),
       }) {
    option->group(kViewFactorGroup);
  }
}

std::vector<std::string> GivenFlagNames(const CLI::App& app) {
  std::vector<std::string> given;
  for (const CLI::Option* option : app.get_options()) {
    if (option->count() > 0 && !option->get_lnames().empty()) {
      given.push_back("--" + option->get_lnames()[0]);
    }
  }
  return given;
}

ViewFactorIntegration RequestedIntegration(const ViewFactorFlags& f) {
  return f.integration == "adaptive"  ? ViewFactorIntegration::kAdaptive
         : f.integration == "patches" ? ViewFactorIntegration::kPatches
                                      : ViewFactorIntegration::kAuto;
}

ViewFactorJobOptions ToViewFactorJobOptions(const ViewFactorFlags& f, const JobOptions& job) {
  ViewFactorJobOptions options;
  options.job = job;
  options.by = f.by == "group"  ? SurfaceGrouping::kGroup
               : f.by == "face" ? SurfaceGrouping::kFace
                                : SurfaceGrouping::kObject;
  options.integration = RequestedIntegration(f);
  options.surface_rows.integration = f.pairs;
  options.surface_rows.threads = job.form_factors.threads;
  options.surface_rows.memory_limit = f.memory_limit;
  options.output.format = *ParseViewFactorFormat(f.format);
  options.output.path = f.output;
  options.output.min_vf = f.min_vf;
  options.output.svf_path = f.svf;
  return options;
}

}  // namespace radflux::cli
