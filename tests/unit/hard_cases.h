// Helpers shared by the hard-case tests of issue 6 (tests/unit/hard_*_test.cc): loading
// scenes/hard/, one knob setting per method, rows kept in double (the precision study)
// and a dense double solve that isolates the storage precision of the rows.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "solver/formfactor/row_builder.h"
#include "solver/scene/obj_loader.h"
#include "solver/scene/validation.h"
#include "solver/solve/solver.h"
#include "test_scenes.h"
#include "tests/source_path.h"

namespace radflux::testing {

inline Scene LoadHardScene(const std::string& name) {
  absl::StatusOr<Scene> scene = LoadObjFile(SourcePath("scenes/hard/") + name);
  EXPECT_TRUE(scene.ok()) << scene.status();
  if (!scene.ok()) return Scene{};
  const absl::Status valid = ValidateScene(*scene);
  EXPECT_TRUE(valid.ok()) << valid;
  return *scene;
}

inline constexpr FormFactorMethod kHardMethods[] = {
    FormFactorMethod::kMonteCarlo, FormFactorMethod::kHemicube, FormFactorMethod::kAnalytic};

// The knob settings of the hard-case tests: k = 1024 rays, r = 64, s = 16; no cut-off.
inline FormFactorOptions HardOptions(FormFactorMethod method) {
  FormFactorOptions o;
  o.method = method;
  o.rays = 1024;
  o.hemicube_res = 64;
  o.samples = 16;
  o.cutoff = 0;
  return o;
}

inline std::string Name(FormFactorMethod m) { return std::string(MethodName(m)); }

inline SolveResult SolveOrDie(const CsrMatrix& f, const PatchAttributes& p, SolverMethod method,
                              double tolerance, int max_iterations) {
  SolverOptions o;
  o.method = method;
  o.tolerance = tolerance;
  o.max_iterations = max_iterations;
  absl::StatusOr<SolveResult> r = Solve({&f, &p}, o);
  EXPECT_TRUE(r.ok()) << r.status();
  return r.ok() ? *r : SolveResult{};
}

inline bool AllFinite(const CsrMatrix& f) {
  return std::all_of(f.value.begin(), f.value.end(), [](float v) { return std::isfinite(v); });
}

// Rows exactly as the builders accumulate them (double), before Flush casts them to float.
using DoubleRows = std::vector<std::vector<std::pair<uint32_t, double>>>;

inline DoubleRows BuildDoubleRows(const RowContext& context, const FormFactorOptions& options) {
  const std::unique_ptr<RowBuilder> builder = MakeRowBuilder(context, options);
  const size_t n = context.mesh->size();
  RowAccumulator acc(n);
  RowBlock discard;
  DoubleRows rows(n);
  for (uint32_t i = 0; i < n; ++i) {
    if (context.needs_row[i]) builder->BuildRow(i, acc);
    for (uint32_t j : acc.Touched()) rows[i].emplace_back(j, acc.Value(j));
    std::sort(rows[i].begin(), rows[i].end());
    acc.Flush(0, discard);
  }
  return rows;
}

// B = E + rho F B for band 0 by dense LU (partial pivoting) in double, with F's values
// rounded to float first when `as_float`: the difference isolates the storage precision.
inline std::vector<double> DenseSolve(const DoubleRows& rows, const PatchAttributes& p,
                                      bool as_float) {
  const size_t n = rows.size();
  std::vector<double> a(n * n, 0.0), b(n);
  for (size_t i = 0; i < n; ++i) {
    a[i * n + i] = 1;
    b[i] = p.emission[i][0];
    for (const auto& [j, v] : rows[i]) {
      const double f = as_float ? static_cast<double>(static_cast<float>(v)) : v;
      a[i * n + j] -= p.reflectance[i][0] * f;
    }
  }
  for (size_t k = 0; k < n; ++k) {
    size_t pivot = k;
    for (size_t r = k + 1; r < n; ++r)
      if (std::abs(a[r * n + k]) > std::abs(a[pivot * n + k])) pivot = r;
    if (pivot != k) {
      for (size_t c = 0; c < n; ++c) std::swap(a[k * n + c], a[pivot * n + c]);
      std::swap(b[k], b[pivot]);
    }
    for (size_t r = k + 1; r < n; ++r) {
      const double m = a[r * n + k] / a[k * n + k];
      if (m == 0) continue;
      for (size_t c = k; c < n; ++c) a[r * n + c] -= m * a[k * n + c];
      b[r] -= m * b[k];
    }
  }
  std::vector<double> x(n);
  for (size_t k = n; k-- > 0;) {
    double s = b[k];
    for (size_t c = k + 1; c < n; ++c) s -= a[k * n + c] * x[c];
    x[k] = s / a[k * n + k];
  }
  return x;
}

// Largest |1 - sum_j F_ij| over rows.
inline double WorstRowSumError(const CsrMatrix& f) {
  double worst = 0;
  for (uint32_t i = 0; i < f.rows; ++i) worst = std::max(worst, std::abs(1 - f.RowSum(i)));
  return worst;
}

}  // namespace radflux::testing

namespace radflux {

// The hard-case tests (tests/unit/hard_*_test.cc) name these unqualified.
using testing::HardOptions;
using testing::LoadHardScene;
using testing::Name;
using testing::RowFixture;
using testing::SolveOrDie;

}  // namespace radflux
