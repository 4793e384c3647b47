#include "solver/formfactor/view_factor_job.h"

#include <algorithm>
#include <chrono>
#include <map>

#include "absl/strings/str_format.h"
#include "solver/core/seconds_since.h"
#include "solver/scene/validation.h"

namespace radflux {
namespace {

ViewFactorSurfaces MakeSurfaces(std::vector<std::string> names, std::vector<double> area,
                                std::vector<double> emittance, const ViewFactorJobOptions& o) {
  ViewFactorSurfaces surfaces;
  surfaces.names = std::move(names);
  surfaces.area = std::move(area);
  surfaces.emittance = std::move(emittance);
  surfaces.enclosure = o.enclosure;
  surfaces.emittances = o.emittances_flag;
  return surfaces;
}

// Writes a dense matrix, freeing each row once written.
absl::Status WriteDense(std::vector<std::vector<double>>& factor, ViewFactorSurfaces surfaces,
                        const ViewFactorOutput& output) {
  absl::StatusOr<std::unique_ptr<ViewFactorWriter>> writer =
      ViewFactorWriter::Open(output, std::move(surfaces));
  if (!writer.ok()) return writer.status();
  for (std::vector<double>& row : factor) {
    if (absl::Status s = (*writer)->WriteRow(row); !s.ok()) return s;
    std::vector<double>().swap(row);
  }
  return (*writer)->Close();
}

}  // namespace

std::optional<FaceSurfaces> SurfacesOfOneFace(const Scene& scene, SurfaceGrouping by) {
  if (!EverySurfaceIsOneFace(scene, by)) return std::nullopt;
  FaceSurfaces out;
  std::vector<SurfaceShape> obstructions;
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const Face& face = scene.faces[f];
    SurfaceShape shape = MakeSurfaceShape(FacePolygon(scene, face));
    shape.opacity = static_cast<float>(scene.materials[face.material].opacity);
    if (face.obstruction) {
      obstructions.push_back(std::move(shape));
      continue;
    }
    const uint32_t name = by == SurfaceGrouping::kGroup ? face.group : face.object;
    out.names.push_back(by == SurfaceGrouping::kFace    ? "face" + std::to_string(f)
                        : by == SurfaceGrouping::kGroup ? scene.groups[name]
                                                        : scene.objects[name]);
    out.emittance.push_back(1 - scene.materials[face.material].reflectance[0]);
    out.shapes.push_back(std::move(shape));
  }
  out.radiating = out.shapes.size();
  for (SurfaceShape& s : obstructions) out.shapes.push_back(std::move(s));
  return out;
}

namespace {

absl::StatusOr<ViewFactorReport> RunAdaptive(FaceSurfaces surfaces,
                                             const ViewFactorJobOptions& options) {
  ViewFactorReport report;
  report.surfaces = surfaces.radiating;
  report.row_sums.allowance = std::max(kRowSumSlack, options.surface_rows.integration.tolerance);
  size_t row_index = 0;
  const auto check = [&](std::span<const double> row) { report.row_sums.Add(row_index++, row); };
  std::vector<double> area;  // opaque areas: what reciprocity and the outputs pair with F
  for (size_t k = 0; k < surfaces.radiating; ++k)
    area.push_back(surfaces.shapes[k].area * surfaces.shapes[k].opacity);
  ViewFactorSurfaces out = MakeSurfaces(surfaces.names, area, surfaces.emittance, options);
  SurfaceRowsStats stats;
  const SurfaceRowsBuilder build = options.build_rows ? options.build_rows : BuildSurfaceRows;
  const auto start = std::chrono::steady_clock::now();
  if (options.enclosure) {  // the adjustment needs the whole matrix
    std::vector<std::vector<double>> factor;
    absl::Status built = build(
        surfaces.shapes, surfaces.radiating, options.surface_rows,
        [&](std::span<const double> row) {
          check(row);
          factor.emplace_back(row.begin(), row.end());
          return absl::OkStatus();
        },
        stats);
    if (!built.ok()) return built;
    report.enclosure = AdjustEnclosure(factor, area);
    if (absl::Status s = WriteDense(factor, std::move(out), options.output); !s.ok()) return s;
  } else {
    absl::StatusOr<std::unique_ptr<ViewFactorWriter>> writer =
        ViewFactorWriter::Open(options.output, std::move(out));
    if (!writer.ok()) return writer.status();
    absl::Status built = build(
        surfaces.shapes, surfaces.radiating, options.surface_rows,
        [&](std::span<const double> row) {
          check(row);
          return (*writer)->WriteRow(row);
        },
        stats);
    if (!built.ok()) return built;
    if (absl::Status s = (*writer)->Close(); !s.ok()) return s;
  }
  report.rows_seconds = stats.rows_seconds + stats.cull_seconds;
  report.write_seconds = SecondsSince(start) - report.rows_seconds;
  report.rays = stats.segments;
  report.patches = surfaces.shapes.size();
  report.adaptive = stats;
  if (!surfaces.names.empty())
    report.row_sums.worst_name = surfaces.names[report.row_sums.worst_row];
  return report;
}

absl::StatusOr<ViewFactorReport> RunPatches(Scene scene, const ViewFactorJobOptions& options) {
  JobOptions job_options = options.job;
  job_options.require_emitter = false;
  job_options.form_factors.exposed_area = false;  // a surface's view factors are of all its area
  absl::StatusOr<std::unique_ptr<PreparedJob>> job = PrepareJob(std::move(scene), job_options);
  if (!job.ok()) return job.status();
  const PreparedJob& prepared = **job;
  ViewFactorReport report;
  report.patches = prepared.mesh.size();
  report.mesh_seconds = prepared.mesh_seconds;
  report.embree_seconds = prepared.embree_seconds;
  RowContext context = prepared.rows;
  for (uint32_t p = 0; p < prepared.mesh.size(); ++p) {  // every surface, black ones too
    context.needs_row[p] = !prepared.scene.faces[prepared.mesh.patches[p].face].obstruction;
  }
  context.emitter.assign(context.emitter.size(), 0);  // a view factor is geometry only
  absl::StatusOr<FormFactorResult> rows = BuildFormFactors(context, options.job.form_factors);
  if (!rows.ok()) return rows.status();
  report.rows_seconds = rows->seconds;
  report.rays = rows->stats.rays;
  const auto start = std::chrono::steady_clock::now();
  SurfaceViewFactors f =
      AggregateViewFactors(prepared.scene, prepared.mesh, rows->matrix, options.by);
  report.surfaces = f.names.size();
  for (size_t s = 0; s < f.factor.size(); ++s) report.row_sums.Add(s, f.factor[s]);
  if (!f.names.empty()) report.row_sums.worst_name = f.names[report.row_sums.worst_row];
  if (options.enclosure) report.enclosure = AdjustEnclosure(f.factor, f.area);
  ViewFactorSurfaces out = MakeSurfaces(f.names, f.area, f.emittance, options);
  if (absl::Status s = WriteDense(f.factor, std::move(out), options.output); !s.ok()) return s;
  report.write_seconds = SecondsSince(start);
  return report;
}

}  // namespace

void RowSumCheck::Add(size_t index, std::span<const double> row) {
  double sum = 0;
  for (double f : row) sum += f;
  if (sum > 1 + allowance) ++rows_over;
  if (index == 0 || sum > worst_sum) {
    worst_sum = sum;
    worst_row = index;
  }
}

std::string RowSumCheck::OverMessage() const {
  return absl::StrFormat(
      "%zu row(s) sum above 1 + %.3g (worst: %s, sum %.4f): view factors overestimated, a "
      "blocker missed or a cluttered pair's visibility (outputs written)",
      rows_over, allowance, worst_name, worst_sum);
}

bool EverySurfaceIsOneFace(const Scene& scene, SurfaceGrouping by) {
  if (by == SurfaceGrouping::kFace) return true;
  std::map<uint32_t, int> faces_per_name;
  for (const Face& face : scene.faces) {
    const uint32_t name = by == SurfaceGrouping::kGroup ? face.group : face.object;
    if (!face.obstruction && ++faces_per_name[name] > 1) return false;
  }
  return true;
}

absl::StatusOr<ViewFactorReport> RunViewFactorJob(Scene scene,
                                                  const ViewFactorJobOptions& options) {
  if (options.integration != ViewFactorIntegration::kPatches) {
    if (absl::Status s = ValidateScene(scene, /*require_emitter=*/false); !s.ok()) return s;
    std::optional<FaceSurfaces> surfaces = SurfacesOfOneFace(scene, options.by);
    if (surfaces) return RunAdaptive(*std::move(surfaces), options);
    if (options.integration == ViewFactorIntegration::kAdaptive) {
      return absl::InvalidArgumentError(
          scene.source +
          ": --integration adaptive needs every surface to be one face (use "
          "--by face, or --integration patches)");
    }
  }
  return RunPatches(std::move(scene), options);
}

}  // namespace radflux
