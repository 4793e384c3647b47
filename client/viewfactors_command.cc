#include "client/viewfactors_command.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "absl/strings/str_format.h"
#include "client/exit_status.h"
#include "client/import_flags.h"
#include "client/job_flags.h"
#include "client/viewfactors_flags.h"
#include "solver/formfactor/view_factor_flags.h"
#include "solver/formfactor/view_factor_job.h"
#include "solver/formfactor/view_factor_scene.h"

namespace radflux::cli {
namespace {

struct ViewFactorArgs {
  std::string scene;
  bool quiet = false;
  std::vector<std::string> given;  // the flags on the command line
  ViewFactorFlags flags;
  JobFlags job;
  ImportFlags import;
};

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
  std::fprintf(stderr, "radflux viewfactors: %s\n", c.OverMessage().c_str());
  return kExitRowSumOver;
}

absl::StatusOr<ViewFactorReport> RunViewFactors(const ViewFactorArgs& args) {
  absl::StatusOr<JobOptions> job = ToJobOptions(args.job);
  if (!job.ok()) return job.status();
  ViewFactorJobOptions options = ToViewFactorJobOptions(args.flags, *job);
  options.surface_rows.progress = !args.quiet && isatty(2);
  absl::StatusOr<ImportOptions> import = ToImportOptions(args.import);
  if (!import.ok()) return import.status();
  absl::StatusOr<ViewFactorScene> model = LoadViewFactorScene(args.scene, *import);
  if (!model.ok()) return model.status();
  PrintImportLog(model->scene.import_log, args.quiet);
  options.enclosure = model->enclosure;
  const ViewFactorIntegration requested = options.integration;
  options.integration =
      ResolveViewFactorIntegration(requested, args.given, model->scene, options.by);
  if (absl::Status s = CheckViewFactorFlags(args.given, args.scene, requested, options.integration);
      !s.ok()) {
    return s;
  }
  return RunViewFactorJob(std::move(model->scene), options);
}

}  // namespace

void AddViewFactorsCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ViewFactorArgs>();
  CLI::App* cmd = app.add_subcommand(
      "viewfactors", "Surface-to-surface view factors between named surfaces (no emitter needed)");
  cmd->add_option("SCENE", args->scene, "scene file (.obj, .gltf, .glb, .mgf, .stl, .vs3)")
      ->required();
  AddViewFactorFlags(*cmd, args->flags, /*output_required=*/true);
  cmd->add_flag("--quiet,-q", args->quiet, "no progress output");
  AddJobFlags(*cmd, args->job);
  AddImportFlags(*cmd, args->import);
  cmd->callback([args, cmd, &exit_code] {
    args->given = GivenFlagNames(*cmd);
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
