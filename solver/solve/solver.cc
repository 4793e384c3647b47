// Solve(): input checks, the per-band view, dispatch to the method, and the final
// residual and band unpacking shared by every method.
#include "solver/solve/solver.h"

#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"
#include "solver/solve/band_system.h"
#include "solver/solve/error_estimate.h"
#include "solver/solve/methods.h"
#include "spdlog/spdlog.h"

namespace radflux {
namespace {

constexpr SolverMethod kAllMethods[] = {SolverMethod::kJacobi,    SolverMethod::kGaussSeidel,
                                        SolverMethod::kSouthwell, SolverMethod::kConjugateGradient,
                                        SolverMethod::kDirect,    SolverMethod::kAuto};

absl::Status CheckMatrix(const CsrMatrix& f, size_t n) {
  if (f.rows != n || f.row_begin.size() != n + 1 || f.col.size() != f.value.size() ||
      f.row_begin.back() != f.col.size()) {
    return absl::InvalidArgumentError(
        absl::StrCat("form-factor matrix has ", f.rows, " rows for ", n, " patches"));
  }
  for (uint32_t c : f.col) {
    if (c >= n)
      return absl::InvalidArgumentError(absl::StrCat("form-factor column ", c, " >= ", n));
  }
  return absl::OkStatus();
}

absl::Status CheckPatches(const PatchAttributes& p) {
  const size_t n = p.size();
  if (p.reflectance.size() != n || p.emission.size() != n) {
    return absl::InvalidArgumentError("patch attributes have inconsistent sizes");
  }
  for (size_t i = 0; i < n; ++i) {
    if (!(p.area[i] > 0) || !std::isfinite(p.area[i])) {
      return absl::InvalidArgumentError(absl::StrCat("patch ", i, " has area ", p.area[i]));
    }
    for (int band = 0; band < kBands; ++band) {
      const double rho = p.reflectance[i][band];
      if (!(rho >= 0 && rho <= 1) || !std::isfinite(p.emission[i][band])) {
        return absl::InvalidArgumentError(
            absl::StrCat("patch ", i, " has reflectance ", rho, " or non-finite emission"));
      }
    }
  }
  return absl::OkStatus();
}

// A row store is checked as rows are appended; here only its shape.
absl::Status CheckRowStore(const RowStore& store, size_t n) {
  if (store.rows() != n || store.cols() != n) {
    return absl::InvalidArgumentError(absl::StrCat("form-factor row store has ", store.rows(),
                                                   " x ", store.cols(), " rows for ", n,
                                                   " patches"));
  }
  return absl::OkStatus();
}

absl::Status CheckInputs(const RadiositySystem& system, const SolverOptions& options) {
  if ((system.form_factors == nullptr) == (system.row_store == nullptr) ||
      system.patches == nullptr) {
    return absl::InvalidArgumentError(
        "radiosity system needs patches and form factors either in memory or in a row store");
  }
  if (!(options.tolerance >= 0) || options.max_iterations < 0 || options.snapshot_every < 0 ||
      options.threads < 0) {
    return absl::InvalidArgumentError(
        "solver options: tolerance, max_iterations, snapshot_every and threads must be >= 0");
  }
  const size_t n = system.patches->size();
  if (options.initial != nullptr && options.initial->size() != n) {
    return absl::InvalidArgumentError(
        absl::StrCat("initial radiosity has ", options.initial->size(), " patches, not ", n));
  }
  if (options.initial_unshot != nullptr &&
      (options.initial == nullptr || options.initial_unshot->size() != n)) {
    return absl::InvalidArgumentError("initial unshot radiosity needs initial radiosity of size n");
  }
  if (absl::Status s = CheckPatches(*system.patches); !s.ok()) return s;
  if (system.row_store != nullptr) return CheckRowStore(*system.row_store, n);
  return CheckMatrix(*system.form_factors, n);
}

absl::Status Dispatch(const BandSystem& bands, const SolverOptions& options,
                      const SolveCallback& callback, std::vector<Rgb>& b, SolveResult& result) {
  switch (options.method) {
    case SolverMethod::kJacobi:
      return SolveJacobi(bands, options, callback, b, result);
    case SolverMethod::kGaussSeidel:
      return SolveGaussSeidel(bands, options, callback, b, result);
    case SolverMethod::kSouthwell:
      return SolveSouthwell(bands, options, callback, b, result);
    case SolverMethod::kConjugateGradient:
      return SolveConjugateGradient(bands, options, callback, b, result);
    case SolverMethod::kDirect:
      return SolveDirect(bands, options, callback, b, result);
    case SolverMethod::kAuto:
      break;  // resolved before dispatch
  }
  return absl::InvalidArgumentError("unknown solver method");
}

// cg's fallback: gauss_seidel from the B cg left, with a budget of its own; its sweeps
// follow cg's in the iteration count and history.
absl::Status FallBack(const BandSystem& bands, const SolverOptions& options,
                      const SolveCallback& callback, std::vector<Rgb>& b, SolveResult& result) {
  spdlog::warn("solver cg gave up after {} iterations ({}); continuing with gauss_seidel",
               result.iterations, result.fallback_reason);
  SolverOptions gs = options;
  gs.method = SolverMethod::kGaussSeidel;
  SolveResult more;
  const int done = result.iterations;
  const SolveCallback shifted = [&](const SolveProgress& p) {
    SolveProgress q = p;
    q.iteration += done;
    if (callback) callback(q);
  };
  if (absl::Status s = Dispatch(bands, gs, shifted, b, more); !s.ok()) return s;
  result.methods_used.push_back(SolverMethod::kGaussSeidel);
  result.iterations += more.iterations;
  result.residual_history.insert(result.residual_history.end(), more.residual_history.begin(),
                                 more.residual_history.end());
  result.converged = more.converged;
  result.cancelled = more.cancelled;
  return absl::OkStatus();
}

// The method, then (cg that gave up) the fallback.
absl::Status RunMethods(const BandSystem& bands, const SolverOptions& options,
                        const SolveCallback& callback, std::vector<Rgb>& b, SolveResult& result) {
  result.methods_used = {options.method};
  if (absl::Status s = Dispatch(bands, options, callback, b, result); !s.ok()) return s;
  if (result.fallback_reason.empty() || result.cancelled) return absl::OkStatus();
  return FallBack(bands, options, callback, b, result);
}

}  // namespace

std::string_view SolverName(SolverMethod method) {
  switch (method) {
    case SolverMethod::kJacobi:
      return "jacobi";
    case SolverMethod::kGaussSeidel:
      return "gauss_seidel";
    case SolverMethod::kSouthwell:
      return "southwell";
    case SolverMethod::kConjugateGradient:
      return "cg";
    case SolverMethod::kDirect:
      return "direct";
    case SolverMethod::kAuto:
      return "auto";
  }
  return "unknown";
}

std::optional<SolverMethod> ParseSolver(std::string_view name) {
  for (SolverMethod method : kAllMethods) {
    if (SolverName(method) == name) return method;
  }
  if (name == "conjugate_gradient") return SolverMethod::kConjugateGradient;
  return std::nullopt;
}

absl::StatusOr<SolveResult> Solve(const RadiositySystem& system, const SolverOptions& options,
                                  const SolveCallback& callback) {
  if (absl::Status s = CheckInputs(system, options); !s.ok()) return s;
  const BandSystem bands = MakeBandSystem(system, options.threads);
  SolverOptions resolved = options;
  resolved.method = ResolveSolver(system, options.method);
  if (system.row_store != nullptr && !StreamsRows(resolved.method)) {
    return absl::FailedPreconditionError(absl::StrCat(
        "solver ", std::string(SolverName(resolved.method)),
        " needs every form-factor row in memory; rows kept in a row store that spills to disk "
        "(--memory-limit) solve with jacobi, gauss_seidel or auto"));
  }
  SolveResult result;
  result.requested = options.method;
  result.method = resolved.method;
  result.bands_solved = bands.lanes;
  std::vector<Rgb> b = options.initial != nullptr ? PackLanes(bands, *options.initial)
                                                  : std::vector<Rgb>(bands.n, Rgb{});
  if (bands.lanes == 0) {  // nothing emits: B = 0 everywhere, no sweep needed
    result.converged = true;
  } else {
    if (absl::Status s = RunMethods(bands, resolved, callback, b, result); !s.ok()) return s;
    std::vector<Rgb> r;
    const absl::StatusOr<Rgb> residual = LaneResiduals(bands, b, &r);
    if (!residual.ok()) return residual.status();
    result.residual = MaxOverLanes(bands, *residual);
    if (absl::Status s = EstimateError(bands, b, r, result); !s.ok()) return s;
  }
  UnpackLanes(bands, b, result.radiosity);
  return result;
}

bool StreamsRows(SolverMethod method) {
  return method == SolverMethod::kJacobi || method == SolverMethod::kGaussSeidel ||
         method == SolverMethod::kAuto;
}

SolverMethod ResolveSolver(const RadiositySystem& system, SolverMethod requested) {
  if (requested != SolverMethod::kAuto) return requested;
  if (system.row_store != nullptr) return SolverMethod::kGaussSeidel;
  double max_rho = 0;
  for (const Rgb& rho : system.patches->reflectance) max_rho = std::max(max_rho, MaxComponent(rho));
  return max_rho > kAutoCgReflectance ? SolverMethod::kConjugateGradient
                                      : SolverMethod::kGaussSeidel;
}

double RelativeResidual(const RadiositySystem& system, const std::vector<Rgb>& radiosity) {
  const BandSystem bands = MakeBandSystem(system, 0);
  if (bands.lanes == 0) return 0;
  const absl::StatusOr<Rgb> residual = LaneResiduals(bands, PackLanes(bands, radiosity), nullptr);
  return residual.ok() ? MaxOverLanes(bands, *residual) : std::nan("");
}

}  // namespace radflux
