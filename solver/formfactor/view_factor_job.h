// `radflux viewfactors` as a library call: scene -> patches -> rows -> surface view factors
// -> (enclosure adjustment) -> the output files. Geometry only: no emitter, no materials
// needed (a material's reflectance gives only View3D's emittance column, 1 - rho).
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>

#include "absl/status/statusor.h"
#include "solver/formfactor/enclosure_adjust.h"
#include "solver/formfactor/surface_rows.h"
#include "solver/formfactor/surface_view_factors.h"
#include "solver/formfactor/view_factor_writer.h"
#include "solver/pipeline.h"

namespace radflux {

// How pairs are integrated: per surface pair as each needs (surface_rows.h; needs every
// surface to be one face), or from patch rows (the form-factor options, any scene).
enum class ViewFactorIntegration { kAuto, kAdaptive, kPatches };

// BuildSurfaceRows' contract (surface_rows.h): what adaptive integration builds its rows with.
using SurfaceRowsBuilder =
    std::function<absl::Status(const std::vector<SurfaceShape>& shapes, size_t radiating,
                               const SurfaceRowsOptions& options, const SurfaceRowSink& sink,
                               SurfaceRowsStats& stats)>;

struct ViewFactorJobOptions {
  ViewFactorIntegration integration = ViewFactorIntegration::kAuto;  // auto: adaptive when
                                                                     // every surface is one face
  SurfaceRowsOptions surface_rows;  // adaptive's options
  JobOptions job;  // patches: meshing and form-factor options (solver options are not used)
  SurfaceGrouping by = SurfaceGrouping::kObject;
  bool enclosure = false;  // adjust for closure and reciprocity (View3D's encl=1)
  bool emittances_flag = false;  // View3D header's emit flag (from a .vs3 C record)
  ViewFactorOutput output;
  // Adaptive rows from this instead of BuildSurfaceRows when set (the service builds them a
  // block at a time with SurfaceRowPlan, checkpointed); the same rows either way.
  SurfaceRowsBuilder build_rows;
};

// Rows whose sum exceeds 1 by more than their error allowance (kRowSumSlack, or the adaptive
// --vf-tolerance when larger): a surface cannot see more than its whole hemisphere, so such
// a row is overestimated (a blocker missed, or the visibility estimate of a cluttered pair).
inline constexpr double kRowSumSlack = 0.01;
struct RowSumCheck {
  double allowance = kRowSumSlack;  // a row may sum to 1 + allowance
  size_t rows_over = 0;             // rows above it
  size_t worst_row = 0;             // the row with the largest sum (0-based surface index)
  double worst_sum = 0;             // its sum
  std::string worst_name;           // its surface's name
  // Counts `row` (surface `index`).
  void Add(size_t index, std::span<const double> row);
  // One line naming the rows over and the worst (when rows_over > 0).
  std::string OverMessage() const;
};

struct ViewFactorReport {
  size_t surfaces = 0, patches = 0;
  uint64_t rays = 0;
  std::optional<SurfaceRowsStats> adaptive;  // set when pairs were integrated adaptively
  double mesh_seconds = 0, embree_seconds = 0, rows_seconds = 0, write_seconds = 0;
  std::optional<EnclosureAdjustment> enclosure;  // set when options.enclosure
  RowSumCheck row_sums;  // of the rows as integrated (before any enclosure adjustment)
};

// Whether every surface of `scene` (by `by`) that is not an obstruction is one face: what
// adaptive integration needs, and what kAuto chooses it by.
bool EverySurfaceIsOneFace(const Scene& scene, SurfaceGrouping by);

// The surfaces when each is one face (what adaptive integration integrates): the radiating
// faces' shapes in order, then the obstruction faces'.
struct FaceSurfaces {
  std::vector<SurfaceShape> shapes;
  size_t radiating = 0;
  std::vector<std::string> names;
  std::vector<double> emittance;
};

// FaceSurfaces of `scene` by `by`; nullopt when some surface has several faces.
std::optional<FaceSurfaces> SurfacesOfOneFace(const Scene& scene, SurfaceGrouping by);

// Computes the view factors of `scene` between its surfaces (options.by) and writes them.
// INVALID_ARGUMENT for a bad scene or options (file:line), errors naming the output file.
absl::StatusOr<ViewFactorReport> RunViewFactorJob(Scene scene, const ViewFactorJobOptions& options);

}  // namespace radflux
