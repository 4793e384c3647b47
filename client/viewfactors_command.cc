#include "client/viewfactors_command.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_format.h"
#include "client/exit_status.h"
#include "client/import_flags.h"
#include "client/job_flags.h"
#include "solver/formfactor/view_factor_job.h"
#include "solver/scene/load_scene.h"
#include "solver/scene/stl_loader.h"
#include "solver/scene/vs3_loader.h"

namespace radflux::cli {
namespace {

// Flags shared with `radflux solve` (job_flags.h, import_flags.h) that mean nothing for view
// factors (issue 23: "no solver options, which mean nothing here"), and the flags of each
// integration: a flag that would do nothing is an error naming it.
constexpr const char* kSolverOnlyFlags[] = {
    "--solver",  "--tolerance",       "--max-iterations",  "--link-epsilon", "--clusters",
    "--min-element-area", "--adaptive-passes", "--adaptive-threshold", "--emit"};
constexpr const char* kImportFlags[] = {"--max-reflectance", "--strict", "--two-sided",
                                        "--curve-segments"};
constexpr const char* kPatchFlags[] = {"--patches", "--max-edge", "--form-factors", "--rays",
                                       "--hemicube-res", "--samples", "--cutoff", "--seed"};
constexpr const char* kAdaptiveFlags[] = {"--vf-tolerance", "--far-ratio", "--middle-ratio",
                                          "--memory-limit"};

struct ViewFactorArgs {
  std::string scene, by = "object", output, format = "csv", svf, integration = "auto";
  double min_vf = 0;
  PairIntegration pairs;
  uint64_t memory_limit = 0;
  bool quiet = false;
  bool form_factors_given = false;  // --form-factors on the command line: auto means patches
  std::vector<std::string> given;   // the flags on the command line
  JobFlags job;
  ImportFlags import;
};

// The scene; a .vs3 file's control record also sets the enclosure adjustment. STL and .vs3
// are read as they are, without the import rules, so that surface k of the output is facet
// or surface record k of the file (what uDALES and View3D users index by).
absl::StatusOr<Scene> LoadViewFactorScene(const ViewFactorArgs& args,
                                          ViewFactorJobOptions& options) {
  const std::string& path = args.scene;
  if (absl::EndsWithIgnoreCase(path, ".stl")) return LoadStlFile(path);
  if (!absl::EndsWithIgnoreCase(path, ".vs3")) {
    absl::StatusOr<ImportOptions> import = ToImportOptions(args.import);
    if (!import.ok()) return import.status();
    absl::StatusOr<Scene> scene = LoadScene(path, *import);
    if (scene.ok()) PrintImportLog(scene->import_log, args.quiet);
    return scene;
  }
  absl::StatusOr<Vs3Model> model = LoadVs3File(path);
  if (!model.ok()) return model.status();
  if (model->control.emittances) {
    return absl::InvalidArgumentError(
        path + ": C emit=1 asks for View3D's interchange factors with emissivities, which "
               "radflux does not compute; set emit=0 for view factors");
  }
  options.enclosure = model->control.enclosure;
  return std::move(model->scene);
}

bool Given(const ViewFactorArgs& args, std::span<const char* const> flags, std::string& which) {
  for (const char* flag : flags) {
    if (std::find(args.given.begin(), args.given.end(), flag) != args.given.end()) {
      which = flag;
      return true;
    }
  }
  return false;
}

// INVALID_ARGUMENT naming the first given flag that does nothing for this scene and
// integration (kAuto already resolved).
absl::Status CheckFlagsApply(const ViewFactorArgs& args, ViewFactorIntegration integration) {
  std::string flag;
  if (Given(args, kSolverOnlyFlags, flag)) {
    return absl::InvalidArgumentError(
        flag + " is for radflux solve only; view factors are geometry only (no emitter, no solver)");
  }
  const bool raw = absl::EndsWithIgnoreCase(args.scene, ".stl") ||
                   absl::EndsWithIgnoreCase(args.scene, ".vs3");
  if (raw && Given(args, kImportFlags, flag)) {
    return absl::InvalidArgumentError(flag + " is an import rule; .stl and .vs3 files are read "
                                             "as they are (surface k = facet or record k)");
  }
  if (integration == ViewFactorIntegration::kAdaptive && Given(args, kPatchFlags, flag)) {
    return absl::InvalidArgumentError(
        flag + " applies to --integration patches; this run integrates per surface pair "
               "(adaptive: every surface is one face)");
  }
  if (integration == ViewFactorIntegration::kPatches && Given(args, kAdaptiveFlags, flag)) {
    return absl::InvalidArgumentError(
        flag + " applies to adaptive integration; this run uses patch rows (" +
        (args.integration == "patches" ? "--integration patches"
         : args.form_factors_given     ? "--form-factors given"
                                       : "a surface with several faces: try --by face") +
        ")");
  }
  return absl::OkStatus();
}

// How the rows fit the memory budget: each pair once, or twice when the triangle does not fit.
std::string MemoryLine(const SurfaceRowsStats& s) {
  const double triangle = static_cast<double>(s.triangle) / (1 << 20);
  const double budget = static_cast<double>(s.budget) / (1 << 20);
  if (s.triangle > s.budget) {
    return absl::StrFormat("rows one by one, each pair twice (the pair triangle's %.0f MiB is "
                           "over the %.0f MiB budget, --memory-limit)",
                           triangle, budget);
  }
  return absl::StrFormat("each pair once (reciprocity: the pair triangle's %.0f MiB within the "
                         "%.0f MiB budget)",
                         triangle, budget);
}

void PrintReport(const ViewFactorReport& r) {
  if (r.adaptive) {
    const SurfaceRowsStats& s = *r.adaptive;
    std::fprintf(stderr,
                 "viewfactors: adaptive pairs: %llu culled (back to back), %llu one-point, %llu "
                 "2 x 2 points, %llu adaptive, %llu exact point-to-surface integrals; %llu possible blockers, %llu "
                 "pairs traced with %llu segments; %s; cull %.2f s, rows %.2f s\n",
                 static_cast<unsigned long long>(s.pairs.culled),
                 static_cast<unsigned long long>(s.pairs.one_point),
                 static_cast<unsigned long long>(s.pairs.middle),
                 static_cast<unsigned long long>(s.pairs.adaptive),
                 static_cast<unsigned long long>(s.pairs.evaluations),
                 static_cast<unsigned long long>(s.blockers),
                 static_cast<unsigned long long>(s.traced_pairs),
                 static_cast<unsigned long long>(s.segments),
                 MemoryLine(s).c_str(), s.cull_seconds,
                 s.rows_seconds);
  }
  std::fprintf(stderr,
               "viewfactors: %zu surfaces (%zu patches); mesh %.2f s, embree %.2f s, rows %.2f s "
               "(%llu rays), adjust+write %.2f s\n",
               r.surfaces, r.patches, r.mesh_seconds, r.embree_seconds, r.rows_seconds,
               static_cast<unsigned long long>(r.rays), r.write_seconds);
  if (!r.enclosure) return;
  const EnclosureAdjustment& e = *r.enclosure;
  for (const auto& [when, err] : {std::pair{"before", e.before}, std::pair{"after", e.after}}) {
    std::fprintf(stderr,
                 "enclosure %s adjustment: max |1 - sum F| %.3g, rms %.3g, max reciprocity %.3g\n",
                 when, err.max_closure, err.rms_closure, err.max_reciprocity);
  }
  if (!e.converged) std::fprintf(stderr, "enclosure: not converged in %d sweeps\n", e.sweeps);
}

// 0, or kExitRowSumOver with one line naming the rows whose sum exceeds 1 beyond the allowance.
int CheckRowSums(const RowSumCheck& c) {
  if (c.rows_over == 0) return 0;
  std::fprintf(stderr,
               "radflux viewfactors: %zu row(s) sum above 1 + %.3g (worst: %s, sum %.4f): view "
               "factors overestimated, a blocker missed or a cluttered pair's visibility "
               "(outputs written)\n",
               c.rows_over, c.allowance, c.worst_name.c_str(), c.worst_sum);
  return kExitRowSumOver;
}

absl::StatusOr<ViewFactorReport> RunViewFactors(const ViewFactorArgs& args) {
  ViewFactorJobOptions options;
  absl::StatusOr<JobOptions> job = ToJobOptions(args.job);
  if (!job.ok()) return job.status();
  options.job = *job;
  options.by = args.by == "group"  ? SurfaceGrouping::kGroup
               : args.by == "face" ? SurfaceGrouping::kFace
                                   : SurfaceGrouping::kObject;
  options.integration = args.integration == "adaptive"  ? ViewFactorIntegration::kAdaptive
                        : args.integration == "patches" ? ViewFactorIntegration::kPatches
                        : args.form_factors_given       ? ViewFactorIntegration::kPatches
                                                        : ViewFactorIntegration::kAuto;
  options.surface_rows.integration = args.pairs;
  options.surface_rows.threads = options.job.form_factors.threads;
  options.surface_rows.memory_limit = args.memory_limit;
  options.surface_rows.progress = !args.quiet && isatty(2);
  options.output.format = *ParseViewFactorFormat(args.format);
  options.output.path = args.output;
  options.output.min_vf = args.min_vf;
  options.output.svf_path = args.svf;
  absl::StatusOr<Scene> scene = LoadViewFactorScene(args, options);
  if (!scene.ok()) return scene.status();
  if (options.integration == ViewFactorIntegration::kAuto) {
    options.integration = EverySurfaceIsOneFace(*scene, options.by)
                              ? ViewFactorIntegration::kAdaptive
                              : ViewFactorIntegration::kPatches;
  }
  if (absl::Status s = CheckFlagsApply(args, options.integration); !s.ok()) return s;
  return RunViewFactorJob(*std::move(scene), options);
}

}  // namespace

void AddViewFactorsCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ViewFactorArgs>();
  CLI::App* cmd = app.add_subcommand(
      "viewfactors", "Surface-to-surface view factors between named surfaces (no emitter needed)");
  cmd->add_option("SCENE", args->scene, "scene file (.obj, .gltf, .glb, .mgf, .stl, .vs3)")
      ->required();
  cmd->add_option("--by", args->by, "what a surface is")
      ->check(CLI::IsMember({"object", "group", "face"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "view-factor file to write")->required();
  cmd->add_option("--format", args->format,
                  "csv (dense, named), sparse (i j F dropped; uDALES vfsparse.inp), view3d "
                  "(View3D's text output)")
      ->check(CLI::IsMember({"csv", "sparse", "view3d"}))
      ->capture_default_str();
  cmd->add_option("--min-vf", args->min_vf,
                  "sparse: leave out F below this; each line's 4th column is its row's dropped sum")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--svf", args->svf, "also write sky view factors 1 - sum_j F_ij, one per line");
  cmd->add_option("--integration", args->integration,
                  "auto (adaptive when every surface is one face and --form-factors is not "
                  "given), adaptive (per surface pair: exact inner integral, one point when far, "
                  "refined where the estimate moves, visibility only where the shaft holds "
                  "geometry) or patches (form-factor rows of the patch mesh)")
      ->check(CLI::IsMember({"auto", "adaptive", "patches"}))
      ->capture_default_str();
  cmd->add_option("--vf-tolerance", args->pairs.tolerance,
                  "adaptive: relative change below which a triangle is not refined")
      ->check(CLI::Range(1e-9, 1.0))
      ->capture_default_str();
  cmd->add_option("--far-ratio", args->pairs.far_ratio,
                  "adaptive: one point when distance / the surface's diameter is at least this")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  cmd->add_option("--middle-ratio", args->pairs.middle_ratio,
                  "adaptive: 2 x 2 Gauss points (no refinement) when distance / the surface's "
                  "diameter is at least this and below --far-ratio")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  cmd->add_option("--memory-limit", args->memory_limit,
                  "adaptive: at most this many bytes of rows in flight (e.g. 64M; default a "
                  "quarter of physical memory): when the triangle of pairs fits, each pair is "
                  "computed once, else rows are computed and written one block at a time")
      ->transform(CLI::AsSizeValue(false));
  cmd->add_flag("--quiet,-q", args->quiet, "no progress output");
  AddJobFlags(*cmd, args->job);
  AddImportFlags(*cmd, args->import);
  cmd->callback([args, cmd, &exit_code] {
    args->form_factors_given = cmd->count("--form-factors") > 0;
    for (const CLI::Option* option : cmd->get_options()) {
      if (option->count() > 0 && !option->get_lnames().empty()) {
        args->given.push_back("--" + option->get_lnames()[0]);
      }
    }
    absl::StatusOr<ViewFactorReport> report = RunViewFactors(*args);
    if (!report.ok()) {
      exit_code = ReportStatus("viewfactors", report.status());
      return;
    }
    PrintReport(*report);
    exit_code = CheckRowSums(report->row_sums);
  });
}

}  // namespace radflux::cli
