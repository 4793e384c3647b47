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
// a handful of cheap sweeps), conjugate_gradient above (where gathering crawls). cg (asked
// for or picked) that meets an indefinite system, diverges or stalls hands its best B to
// gauss_seidel, which converges for any rho < 1 (SolveResult::fallback_reason says why).
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
  double tolerance = 1e-4;    // stop when the residual measure (RelativeResidual) <= this
  int max_iterations = 1000;  // sweeps (jacobi, gauss_seidel, cg; a fallback gets as many
                              // again), or southwell's sweep-equivalents (batches that shot
                              // as many entries as the rows hold)
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
  double residual = 0;         // the stopping measure (RelativeResidual), max over bands
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
  double residual = 0;                   // final RelativeResidual (max over bands)
  std::vector<double> residual_history;  // per iteration: the stopping measure (of B at the
                                         // sweep's start; southwell: at each sweep-equivalent)
  bool converged = false;
  bool cancelled = false;
  SolverMethod requested = SolverMethod::kConjugateGradient;  // as asked (may be kAuto)
  SolverMethod method = SolverMethod::kConjugateGradient;  // the method that ran first (never
                                                           // kAuto)
  std::vector<SolverMethod> methods_used;  // in order: method, then a fallback if one ran
  std::string fallback_reason;             // why cg handed over to gauss_seidel ("" if not)
  // Estimated error left in B: max_i |B*_i - B_i| / max_i |B_i - E_i| (max over bands),
  // from the bound ||r||_inf / (1 - q), q = max_i rho_i sum_j F_ij < 1 (the rows as a
  // contraction); when q >= 1, from the observed contraction rate c of the last iterations,
  // residual / (1 - c). error_estimate_method names which ("bound" or "rate"; "" if none).
  double error_estimate = 0;
  std::string error_estimate_method;
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

// ||E + rho F B - B||_A / ||rho F B||_A (area-weighted 2-norms; ||E||_A where rho F B = 0),
// max over bands: the residual against the reflected part of the same B, the stopping
// measure of every method. NaN when rows in a store cannot be read back.
double RelativeResidual(const RadiositySystem& system, const std::vector<Rgb>& radiosity);

}  // namespace radflux
