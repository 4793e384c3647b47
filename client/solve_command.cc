#include "client/solve_command.h"

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/str_format.h"
#include "client/exit_status.h"
#include "client/import_flags.h"
#include "client/job_flags.h"
#include "client/output_flags.h"
#include "client/progress_display.h"
#include "solver/core/parallel.h"
#include "solver/report.h"
#include "solver/scene/load_scene.h"

namespace radflux::cli {
namespace {

struct SolveArgs {
  std::string scene;
  JobFlags job;
  ImportFlags import;
  OutputFlags output;
  bool quiet = false;
  uint64_t memory_limit = 0;  // bytes of rows kept in memory (0 = all)
  std::string spill_dir;
  bool view = false;  // --view: the solve's page in the browser
  int view_port = 0;
};

absl::Status WriteReport(const std::string& path, const nlohmann::json& report) {
  std::ofstream file(path);
  file << report.dump(2) << "\n";
  file.close();
  if (!file) return absl::InternalError("cannot write report file '" + path + "'");
  return absl::OkStatus();
}

// What hierarchical radiosity or adaptive meshing built, one line each (also in the report).
std::vector<std::string> RefinementLines(const JobResult& result) {
  std::vector<std::string> lines;
  if (const std::optional<HierarchicalStats>& h = result.hierarchical) {
    lines.push_back(absl::StrFormat(
        "hierarchical: %d faces, %d clusters, %d elements, %d leaves -> %d conforming patches; "
        "%d links (%.2f MB links, %.2f MB elements) from %d initial links; %d passes, %d "
        "refine rounds, %d rays; refine %.3fs gather %.3fs",
        h->roots, h->clusters, h->elements, h->leaves, h->patches, h->links, h->link_bytes / 1e6,
        h->element_bytes / 1e6, h->initial_links, h->passes, h->refine_rounds, h->rays,
        h->refine_seconds, h->solve_seconds));
  }
  for (size_t k = 0; k < result.adaptive_passes.size(); ++k) {
    const AdaptivePass& p = result.adaptive_passes[k];
    lines.push_back(absl::StrFormat(
        "adaptive pass %d: %d patches (%d split), %d rows recomputed, %d entries, %.3fs, change "
        "in B %.3e",
        k, p.patches, p.split, p.rows_recomputed, p.entries_computed, p.seconds, p.change_in_b));
  }
  return lines;
}

// How the solve itself ended (outputs are written either way).
struct SolveOutcome {
  bool converged = true;
  int iterations = 0;
  double residual = 0, tolerance = 0;
  std::string balance_off;  // EnergyBalance::OffMessage(), empty when the balance closed
};

// The observer of --view (null without it). Hierarchical and adaptive solves change the
// mesh as they go, which the page (one mesh, then B per patch) cannot follow.
absl::StatusOr<std::unique_ptr<SolveObserver>> MakeObserver(const SolveArgs& args,
                                                            const JobOptions& options,
                                                            const SolveObserverFactory& view) {
  if (!args.view) return nullptr;
  if (!view) {
    return absl::FailedPreconditionError(
        "--view is served by radflux-service: run it as `radflux solve ... --view`");
  }
  if (options.hierarchical.enabled || options.adaptive.passes > 0) {
    return absl::InvalidArgumentError(
        "--view shows uniform meshes only (not --solver hierarchical or --adaptive-passes)");
  }
  return view(args.view_port);
}

absl::Status RunSolve(const SolveArgs& args, const SolveObserverFactory& view,
                      SolveOutcome& outcome, std::unique_ptr<SolveObserver>& observer) {
  absl::StatusOr<JobOptions> options = ToJobOptions(args.job);
  if (!options.ok()) return options.status();
  const ScopedThreadCount job_threads(options->form_factors.threads);  // every phase
  absl::StatusOr<std::unique_ptr<SolveObserver>> made = MakeObserver(args, *options, view);
  if (!made.ok()) return made.status();
  observer = *std::move(made);
  if (observer) options->solver.snapshot_every = 1;
  options->spill.memory_limit = args.memory_limit;
  options->spill.directory = args.spill_dir;
  options->find_indirect = DrawsDirectPerPixel(args.output);
  if (absl::Status s = ValidateJobOptions(*options); !s.ok()) return s;
  if (absl::Status s = ValidateOutputFlags(args.output); !s.ok()) return s;
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<ImportOptions> import = ToImportOptions(args.import);
  if (!import.ok()) return import.status();
  absl::StatusOr<Scene> scene = LoadScene(args.scene, *import);
  if (!scene.ok()) return scene.status();
  PrintImportLog(scene->import_log, args.quiet);
  if (observer) {
    if (absl::Status s = observer->Start(*scene, *options); !s.ok()) return s;
  }
  const double load_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  ProgressDisplay progress(args.quiet);
  JobCallbacks callbacks;
  callbacks.phase = [&](std::string_view phase, int64_t done, int64_t total) {
    progress.Phase(phase, done, total);
    if (observer) observer->Phase(done, total);
    return true;
  };
  callbacks.solve = [&](const SolveProgress& p) {
    progress.Iteration(p.iteration, p.residual, p.unshot_fraction);
    if (observer) observer->Iteration(p);
  };
  absl::StatusOr<JobResult> result = RunJob(*std::move(scene), *options, callbacks);
  if (!result.ok()) return result.status();
  progress.Finish();
  const PreparedJob& job = *result->job;
  outcome = {result->solve.converged, result->solve.iterations, result->solve.residual,
             options->solver.tolerance, ""};
  if (const absl::StatusOr<EnergyBalance>& balance = SettleEnergyBalance(*result, *options);
      balance.ok()) {
    outcome.balance_off = balance->OffMessage();
  }
  progress.Line(
      absl::StrFormat("%d patches, %d non-zeros (%.1f MB), %d iterations, residual %.2e; "
                      "mesh %.3fs embree %.3fs rows %.3fs solve %.3fs",
                      job.mesh.size(), result->RowNonZeros(), result->RowBytes() / 1e6,
                      result->solve.iterations, result->solve.residual, result->timings.mesh,
                      result->timings.embree, result->timings.rows, result->timings.solve));
  for (const std::string& line : RefinementLines(*result)) progress.Line(line);

  const auto output_start = std::chrono::steady_clock::now();
  OutputTimings output_timings;
  if (absl::Status s =
          WriteOutputs(args.output, job.scene, job.mesh, result->solve.radiosity, result->indirect,
                       args.job.seed, args.job.threads, &output_timings);
      !s.ok()) {
    return s;
  }
  if (args.output.gather > 0 && !args.output.render.empty()) {
    progress.Line(absl::StrFormat("final gather: %d rays per pixel at %s, %.3fs (solve %.3fs)",
                                  args.output.gather, args.output.size, output_timings.gather,
                                  result->timings.solve));
  }
  if (!args.output.report.empty() || observer) {
    nlohmann::json report = MakeJobReport(*result, *options, args.scene);
    report["seconds"]["load"] = load_seconds;
    if (args.output.gather > 0) report["seconds"]["gather"] = output_timings.gather;
    report["seconds"]["output"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - output_start).count();
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    report["peak_rss_bytes"] = static_cast<int64_t>(usage.ru_maxrss) * 1024;
    if (observer) observer->Finish(*result, report);
    if (args.output.report.empty()) return absl::OkStatus();
    if (absl::Status s = WriteReport(args.output.report, report); !s.ok()) return s;
  }
  return absl::OkStatus();
}

}  // namespace

void AddSolveCommand(CLI::App& app, int& exit_code, SolveObserverFactory view) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* solve = app.add_subcommand(
      "solve", "Solve a scene in-process (no server): mesh, form factors, radiosity, outputs");
  solve->add_option("SCENE", args->scene, "scene file (.obj with its .mtl, .gltf, .glb, .mgf)")
      ->required();
  AddJobFlags(*solve, args->job);
  AddImportFlags(*solve, args->import);
  AddOutputFlags(*solve, args->output);
  solve->add_flag("--quiet,-q", args->quiet, "no progress output");
  solve
      ->add_option("--memory-limit", args->memory_limit,
                   "keep at most this many bytes of form-factor rows in memory (e.g. 512M, 2G); "
                   "the rest spill to disk and stream back each sweep (jacobi, gauss_seidel, "
                   "auto)")
      ->transform(CLI::AsSizeValue(false));
  solve->add_option("--spill-dir", args->spill_dir,
                    "with --memory-limit: directory for the spill file (default: a fresh "
                    "directory under $TMPDIR or /tmp, removed at the end)");
  solve->add_flag("--view", args->view,
                  "watch the solve in the browser (as `radflux view JOB`): prints a URL on "
                  "127.0.0.1 and keeps serving the page after the solve, until Ctrl-C");
  solve->add_option("--view-port", args->view_port, "with --view: port (default: a free one)")
      ->check(CLI::Range(0, 65535));
  solve->callback([args, view, &exit_code] {
    SolveOutcome outcome;
    std::unique_ptr<SolveObserver> observer;
    exit_code = ReportStatus("solve", RunSolve(*args, view, outcome, observer));
    if (exit_code == 0 && !outcome.converged) {
      exit_code =
          ReportNotConverged("solve", outcome.iterations, outcome.residual, outcome.tolerance);
    } else if (exit_code == 0 && !outcome.balance_off.empty()) {
      exit_code = ReportEnergyImbalance("solve", outcome.balance_off);
    }
    // The page stays for a solve that ended (converged or not), not for a failed one.
    if (observer && (exit_code == 0 || exit_code == kExitNotConverged)) {
      observer->ServeUntilStopped();
    }
  });
}

}  // namespace radflux::cli
