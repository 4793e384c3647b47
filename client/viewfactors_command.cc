#include "client/viewfactors_command.h"

#include <cstdio>
#include <memory>

#include "client/exit_status.h"
#include "client/import_flags.h"
#include "client/job_flags.h"
#include "solver/formfactor/surface_view_factors.h"
#include "solver/pipeline.h"
#include "solver/scene/load_scene.h"

namespace radflux::cli {
namespace {

struct ViewFactorArgs {
  std::string scene, by = "object", output;
  JobFlags job;
  ImportFlags import;
};

absl::Status RunViewFactors(const ViewFactorArgs& args) {
  absl::StatusOr<JobOptions> options = ToJobOptions(args.job);
  if (!options.ok()) return options.status();
  absl::StatusOr<ImportOptions> import = ToImportOptions(args.import);
  if (!import.ok()) return import.status();
  absl::StatusOr<Scene> scene = LoadScene(args.scene, *import);
  if (!scene.ok()) return scene.status();
  PrintImportLog(scene->import_log, /*quiet=*/false);
  absl::StatusOr<std::unique_ptr<PreparedJob>> job = PrepareJob(*std::move(scene), *options);
  if (!job.ok()) return job.status();
  RowContext context = (*job)->rows;
  context.needs_row.assign(context.needs_row.size(), 1);  // every surface, black ones too
  context.emitter.assign(context.emitter.size(), 0);      // a view factor is geometry only
  absl::StatusOr<FormFactorResult> rows = BuildFormFactors(context, options->form_factors);
  if (!rows.ok()) return rows.status();
  const SurfaceGrouping by = args.by == "group"  ? SurfaceGrouping::kGroup
                             : args.by == "face" ? SurfaceGrouping::kFace
                                                 : SurfaceGrouping::kObject;
  return WriteViewFactorsCsv(args.output,
                             AggregateViewFactors((*job)->scene, (*job)->mesh, rows->matrix, by));
}

}  // namespace

void AddViewFactorsCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ViewFactorArgs>();
  CLI::App* cmd = app.add_subcommand(
      "viewfactors", "Surface-to-surface view factors between named surfaces, as CSV");
  cmd->add_option("SCENE", args->scene, "scene file (Wavefront OBJ with MTL)")->required();
  cmd->add_option("--by", args->by, "what a surface is")
      ->check(CLI::IsMember({"object", "group", "face"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "view-factor CSV to write")->required();
  AddJobFlags(*cmd, args->job);
  AddImportFlags(*cmd, args->import);
  cmd->callback(
      [args, &exit_code] { exit_code = ReportStatus("viewfactors", RunViewFactors(*args)); });
}

}  // namespace radflux::cli
