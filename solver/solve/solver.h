// The radiosity solvers: B = E + rho * F * B per colour band, for the patches of a
// mesh and their form-factor rows. Every method shares one stopping rule (tolerance,
// maximum iterations, cancellation, whichever comes first) and reports progress
// through one callback, which is how snapshots reach a watcher.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/sparse/csr_matrix.h"
#include "solver/sparse/row_store.h"

namespace radflux {

// kAuto picks per scene: gauss_seidel while max rho <= kAutoCgReflectance (it converges in
// a handful of cheap sweeps), conjugate_gradient above (where gathering crawls).
enum class SolverMethod { kJacobi, kGaussSeidel, kSouthwell, kConjugateGradient, kDirect, kAuto };
inline constexpr double kAutoCgReflectance = 0.9;

// Largest system the direct method accepts (larger: RESOURCE_EXHAUSTED). Dense LU holds
// n^2 doubles (128 MB at 4000) and costs n^3/3 flops per distinct reflectance band
// (~21 GFlop at 4000); beyond that an iterative method is both smaller and faster.
inline constexpr size_t kMaxDirectPatches = 4000;

std::string_view SolverName(
    SolverMethod method);  // "jacobi", "gauss_seidel", "southwell", "cg", "direct"
std::optional<SolverMethod> ParseSolver(std::string_view name);

// The linear system of one job: rows F (n x n) and per-patch area, rho and E. The rows
// are either in memory (form_factors) or in a row store that may have spilled them to
// disk (row_store): only jacobi and gauss_seidel stream rows, so with a store kAuto is
// gauss_seidel and cg, southwell and direct are refused (FAILED_PRECONDITION).
struct RadiositySystem {
  const CsrMatrix* form_factors = nullptr;
  const PatchAttributes* patches = nullptr;
  const RowStore* row_store = nullptr;  // instead of form_factors
};

// Whether `method` can solve from rows streamed out of a RowStore.
bool StreamsRows(SolverMethod method);

struct SolverOptions {
  SolverMethod method = SolverMethod::kConjugateGradient;
  double tolerance = 1e-4;    // stop when the measure (residual or unshot fraction) <= this
  int max_iterations = 1000;  // sweeps (jacobi, gauss_seidel, cg) or shooting batches (southwell)
  int threads = 0;            // 0 = all cores
  int snapshot_every = 0;     // include B in the callback every N iterations (0 = never)
  const std::atomic<bool>* cancel = nullptr;  // set by the caller to stop at the next sweep
  const std::vector<Rgb>* initial = nullptr;  // warm start / checkpoint resume (size n) or null
  // Southwell only, with `initial`: the unshot radiosity saved with it (SolveProgress::
  // state_unshot); the solve then continues exactly (bit for bit) where that state was taken.
  const std::vector<Rgb>* initial_unshot = nullptr;
};

// One progress report. `snapshot` is non-null only on snapshot iterations and is valid
// for the duration of the call.
struct SolveProgress {
  int iteration = 0;
  double residual = 0;         // relative residual ||E + rho F B - B|| / ||E||, max over bands;
                               // southwell: the bound max(rho) ||dB|| / ||E|| (exact for
                               // reciprocal rows), its true residual is in SolveResult
  double unshot_fraction = 0;  // southwell: unshot power / emitted power (else 0)
  const std::vector<Rgb>* snapshot = nullptr;
  // On snapshot iterations, the solver state to resume from (SolverOptions::initial and,
  // for southwell, initial_unshot): the iterate B (equal to `snapshot` except for southwell,
  // whose snapshot adds the ambient term) and southwell's unshot radiosity (else null).
  const std::vector<Rgb>* state = nullptr;
  const std::vector<Rgb>* state_unshot = nullptr;
};
using SolveCallback = std::function<void(const SolveProgress&)>;

struct SolveResult {
  std::vector<Rgb> radiosity;  // B per patch per band, W/m^2
  int iterations = 0;
  double residual = 0;                   // final relative residual (max over bands)
  std::vector<double> residual_history;  // per iteration: the stopping measure (the residual
                                         // of B at the sweep's start; southwell: unshot fraction)
  bool converged = false;
  bool cancelled = false;
  SolverMethod method = SolverMethod::kConjugateGradient;  // the method that ran (never kAuto)
  int bands_solved = 3;                                    // 1 when the scene is grey
  double reciprocity_error = 0;  // cg: max |A_i F_ij - A_j F_ji| / max(A_i F_ij, A_j F_ji)
                                 // over pairs where both entries are stored
  int64_t one_sided_pairs = 0;   // cg: pairs stored one way only (both rows non-empty)
  double unshot_fraction = 0;    // southwell: final unshot power / emitted power
};

// The method `requested` stands for on this system (itself unless it is kAuto).
SolverMethod ResolveSolver(const RadiositySystem& system, SolverMethod requested);

absl::StatusOr<SolveResult> Solve(const RadiositySystem& system, const SolverOptions& options,
                                  const SolveCallback& callback = {});

// ||E + rho F B - B|| / ||E|| (area-weighted 2-norm), max over bands; the shared stopping
// measure. NaN when rows in a store cannot be read back.
double RelativeResidual(const RadiositySystem& system, const std::vector<Rgb>& radiosity);

}  // namespace radflux
