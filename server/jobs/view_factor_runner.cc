#include "server/jobs/view_factor_runner.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "nlohmann/json.hpp"
#include "server/jobs/progress_throttle.h"
#include "server/jobs/view_factor_rows.h"
#include "solver/formfactor/view_factor_flags.h"
#include "solver/scene/validation.h"
#include "wire/proto_convert.h"
#include "wire/view_factor_convert.h"

namespace radflux {
namespace {

using Clock = std::chrono::steady_clock;

// Bytes of a file per ViewFactorFileChunk: far below gRPC's 4 MB message limit.
constexpr size_t kFileChunkBytes = size_t{1} << 20;

absl::StatusOr<std::string> ReadWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) return absl::InternalError("cannot read back the job's file " + path);
  return bytes.str();
}

void AddFileChunks(v1::ViewFactorFile file, const std::string& bytes,
                   std::vector<v1::ResultChunk>& chunks) {
  for (size_t at = 0; at < bytes.size(); at += kFileChunkBytes) {
    v1::ViewFactorFileChunk* chunk = chunks.emplace_back().mutable_view_factor_file();
    chunk->set_file(file);
    chunk->set_offset(at);
    chunk->set_data(bytes.substr(at, kFileChunkBytes));
  }
}

nlohmann::json ErrorJson(const EnclosureError& e) {
  return {{"max_closure", e.max_closure},
          {"rms_closure", e.rms_closure},
          {"max_reciprocity", e.max_reciprocity}};
}

// The report: what `radflux viewfactors` prints, as JSON.
std::string ReportJson(const ViewFactorReport& r, const ViewFactorRun& run,
                       const ViewFactorRowsReport& rows) {
  // run.model.scene was moved into the job: only its name is read here.
  nlohmann::json j = {
      {"scene", run.model_name},
      {"surfaces", r.surfaces},
      {"patches", r.patches},
      {"rays", r.rays},
      {"integration", r.adaptive ? "adaptive" : "patches"},
      {"timings", {{"mesh", r.mesh_seconds}, {"embree", r.embree_seconds},
                   {"rows", r.rows_seconds}, {"write", r.write_seconds}}},
      {"row_sums", {{"allowance", r.row_sums.allowance}, {"rows_over", r.row_sums.rows_over},
                    {"worst_row", r.row_sums.worst_row}, {"worst_sum", r.row_sums.worst_sum},
                    {"worst_name", r.row_sums.worst_name}}}};
  j["reused_rows"] = rows.reused_rows;  // from a resumed job's stored blocks (not in the counts)
  j["workers"] = WorkersJson(rows.farm);
  if (r.adaptive) {
    const SurfaceRowsStats& s = *r.adaptive;
    j["adaptive"] = {{"culled", s.pairs.culled},         {"one_point", s.pairs.one_point},
                     {"middle", s.pairs.middle},         {"adaptive", s.pairs.adaptive},
                     {"evaluations", s.pairs.evaluations}, {"blockers", s.blockers},
                     {"traced_pairs", s.traced_pairs},   {"segments", s.segments},
                     {"reciprocal", s.reciprocal},       {"budget_bytes", s.budget},
                     {"triangle_bytes", s.triangle}};
  }
  if (r.enclosure) {
    j["enclosure"] = {{"before", ErrorJson(r.enclosure->before)},
                      {"after", ErrorJson(r.enclosure->after)},
                      {"sweeps", r.enclosure->sweeps},
                      {"converged", r.enclosure->converged}};
  }
  return j.dump(2);
}

// The result stream of the job's two files and its report, encoded for the store.
absl::StatusOr<EncodedResult> EncodeFiles(const ViewFactorOutput& output, const std::string& report) {
  absl::StatusOr<std::string> factors = ReadWholeFile(output.path);
  if (!factors.ok()) return factors.status();
  absl::StatusOr<std::string> sky = ReadWholeFile(output.svf_path);
  if (!sky.ok()) return sky.status();
  std::vector<v1::ResultChunk> chunks(1);
  chunks[0].mutable_header()->set_view_factor_bytes(factors->size());
  chunks[0].mutable_header()->set_sky_view_factor_bytes(sky->size());
  AddFileChunks(v1::VIEW_FACTOR_FILE_FACTORS, *factors, chunks);
  AddFileChunks(v1::VIEW_FACTOR_FILE_SKY, *sky, chunks);
  chunks.emplace_back().set_report_json(report);
  EncodedResult result;
  result.bytes = EncodeResultChunks(chunks);
  BlobBuilder blob;
  if (absl::Status s = blob.Append(result.bytes); !s.ok()) return s;
  result.file = blob.File();
  return result;
}

// Progress of the surface rows to the job's watchers; false once the job is to stop.
std::function<bool(size_t, size_t)> RowProgress(ProgressThrottle& throttle, const RunContext& c) {
  const auto start = Clock::now();
  return [&throttle, &c, start](size_t done, size_t total) {
    v1::JobEvent event;
    event.set_state(v1::JOB_STATE_RUNNING);
    event.set_phase(v1::PHASE_ROWS);
    event.mutable_progress()->set_rows_done(static_cast<int64_t>(done));
    event.mutable_progress()->set_rows_total(static_cast<int64_t>(total));
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (done > 0) {
      event.mutable_progress()->set_eta_seconds(seconds / static_cast<double>(done) *
                                                static_cast<double>(total - done));
    }
    throttle.Publish(std::move(event));
    return !(c.stop && c.stop->load());
  };
}

}  // namespace

absl::StatusOr<ViewFactorRun> PrepareViewFactorRun(const v1::SolveOptions& request,
                                                   StoredScene stored) {
  ViewFactorRun run;
  run.model_name = StoredModelName(stored);
  absl::StatusOr<ImportOptions> import = FromProto(request.import_options());
  if (!import.ok()) return import.status();
  absl::StatusOr<ViewFactorScene> model = LoadStoredViewFactorScene(std::move(stored), *import);
  if (!model.ok()) return model.status();
  if (absl::Status s = ValidateScene(model->scene, /*require_emitter=*/false); !s.ok()) return s;
  absl::StatusOr<ViewFactorJobOptions> options = ViewFactorJobOptionsFromProto(request);
  if (!options.ok()) return options.status();
  const std::vector<std::string> given = ViewFactorFlagsOf(request);
  const ViewFactorIntegration requested = options->integration;
  options->integration = ResolveViewFactorIntegration(requested, given, model->scene, options->by);
  if (absl::Status s = CheckViewFactorFlags(given, run.model_name, requested, options->integration);
      !s.ok()) {
    return s;
  }
  if (options->integration == ViewFactorIntegration::kPatches) {
    if (absl::Status s = ValidateJobOptions(options->job); !s.ok()) return s;
  }
  options->enclosure = model->enclosure;
  run.surfaces = ViewFactorSurfaceCount(model->scene, options->by);
  run.model = *std::move(model);
  run.options = *std::move(options);
  return run;
}

uint64_t ViewFactorDiskBound(const ViewFactorRun& run) {
  const double n = static_cast<double>(run.surfaces);
  const ViewFactorOutput& out = run.options.output;
  // Characters per entry: csv %.9g and a comma, view3d %.6f and a space, sparse "i j F d".
  double entries = n * n, per_entry = out.format == ViewFactorFormat::kView3d ? 10 : 17;
  if (out.format == ViewFactorFormat::kSparse) {
    per_entry = 64;
    // A row sums to at most about 1: at most 1 / min_vf entries of it reach min_vf.
    if (out.min_vf > 0) entries = std::min(entries, n * (1.5 / out.min_vf + 1));
  }
  const double file = entries * per_entry + n * 80;  // names, areas, emittances, sky factors
  const double blocks = n * n * sizeof(double);      // the checkpointed rows, at most
  return static_cast<uint64_t>(std::min(blocks + 2 * file, 1e18));  // + the files, the result
}

absl::StatusOr<EncodedResult> RunStoredViewFactorJob(const v1::Job& job, const RunContext& c) {
  c.on_phase(v1::PHASE_PREPARE, 0);
  absl::StatusOr<StoredScene> stored = c.store->GetScene(job.scene_sha256());
  if (!stored.ok()) return stored.status();
  absl::StatusOr<ViewFactorRun> run = PrepareViewFactorRun(job.options(), *std::move(stored));
  if (!run.ok()) return run.status();
  run->options.job.form_factors.threads = c.threads;
  run->options.surface_rows.threads = c.threads;
  if (run->options.surface_rows.memory_limit == 0 && c.max_memory != UINT64_MAX) {
    run->options.surface_rows.memory_limit = c.max_memory;  // the server's memory per job
  }
  const std::string dir = c.store->JobDir(job.job_id());
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  ViewFactorJobOptions& options = run->options;  // outputs into the job's directory
  options.output.path = dir + "/view_factors.out";
  options.output.svf_path = dir + "/sky_view_factors.out";
  ProgressThrottle throttle(*c.hub, JobHub::kWakeInterval, std::chrono::milliseconds(100));
  options.surface_rows.on_rows = RowProgress(throttle, c);
  ViewFactorRowsReport rows_report;
  options.build_rows = FarmedViewFactorRows(job, c, rows_report);
  c.on_phase(v1::PHASE_ROWS, static_cast<int64_t>(run->surfaces));
  absl::StatusOr<ViewFactorReport> report = RunViewFactorJob(std::move(run->model.scene), options);
  throttle.Flush();
  if (c.stop && c.stop->load()) return absl::CancelledError("stopped during view-factor rows");
  if (!report.ok()) return report.status();
  absl::StatusOr<EncodedResult> result =
      EncodeFiles(options.output, ReportJson(*report, *run, rows_report));
  if (result.ok() && report->row_sums.rows_over > 0) {
    result->energy_balance_ok = false;
    result->message = report->row_sums.OverMessage();
  }
  return result;
}

}  // namespace radflux
