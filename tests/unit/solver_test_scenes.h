// Small radiosity systems with known answers for the solver tests.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "solver/mesh/patch_attributes.h"
#include "solver/solve/solver.h"
#include "solver/sparse/csr_matrix.h"

namespace radflux::testing {

// A system that owns its rows and patches.
struct TestSystem {
  CsrMatrix f;
  PatchAttributes patches;
  RadiositySystem View() const { return {&f, &patches}; }
};

inline CsrMatrix FromRows(const std::vector<std::map<uint32_t, double>>& rows) {
  CsrMatrix f;
  f.cols = static_cast<uint32_t>(rows.size());
  RowBlock block;
  for (const auto& row : rows) {
    for (const auto& [j, v] : row) block.Add(j, static_cast<float>(v));
    block.EndRow();
  }
  f.Append(block);
  return f;
}

// Closed, exactly reciprocal rows for n equal-area patches: F = sum over `shifts` of
// (C_s + C_-s) / (2 |shifts|) with the patches relabelled by a seeded permutation.
// Symmetric, rows sum to exactly 1 (entries are 1/8 for 4 shifts), zero diagonal.
inline TestSystem ClosedEqualArea(uint32_t n, double rho, double emission, uint32_t seed = 7) {
  const std::vector<uint32_t> shifts = {1, 5, 13, 22};
  std::vector<uint32_t> label(n);
  for (uint32_t i = 0; i < n; ++i) label[i] = i;
  std::shuffle(label.begin(), label.end(), std::mt19937(seed));
  std::vector<std::map<uint32_t, double>> rows(n);
  const double w = 1.0 / (2 * shifts.size());
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t s : shifts) {
      rows[label[i]][label[(i + s) % n]] += w;
      rows[label[i]][label[(i + n - s % n) % n]] += w;
    }
  TestSystem t;
  t.f = FromRows(rows);
  t.patches.area.assign(n, 0.25);
  t.patches.reflectance.assign(n, Rgb{rho, rho, rho});
  t.patches.emission.assign(n, Rgb{emission, emission, emission});
  t.patches.grey = true;
  return t;
}

// Closed reciprocal rows with unequal areas: a random symmetric sparse W, A_i = sum_j W_ij,
// F_ij = W_ij / A_i (reciprocal and row sums 1 up to float rounding).
inline TestSystem ClosedUnequalArea(uint32_t n, int neighbours, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.1, 1.0);
  std::uniform_int_distribution<uint32_t> pick(0, n - 1);
  std::vector<std::map<uint32_t, double>> w(n);
  for (uint32_t i = 0; i < n; ++i)
    for (int k = 0; k < neighbours; ++k) {
      const uint32_t j = pick(rng);
      if (j == i) continue;
      const double v = u(rng);
      w[i][j] += v;
      w[j][i] += v;
    }
  TestSystem t;
  t.patches.area.assign(n, 0);
  for (uint32_t i = 0; i < n; ++i)
    for (const auto& [j, v] : w[i]) t.patches.area[i] += v;
  for (uint32_t i = 0; i < n; ++i)
    for (auto& [j, v] : w[i]) v /= t.patches.area[i];
  t.f = FromRows(w);
  t.patches.reflectance.assign(n, Rgb{0.5, 0.5, 0.5});
  t.patches.emission.assign(n, Rgb{});
  t.patches.grey = false;
  return t;
}

inline SolverOptions Options(SolverMethod method, double tolerance, int max_iterations,
                             int threads = 1) {
  SolverOptions o;
  o.method = method;
  o.tolerance = tolerance;
  o.max_iterations = max_iterations;
  o.threads = threads;
  return o;
}

inline constexpr SolverMethod kIterativeMethods[] = {
    SolverMethod::kJacobi, SolverMethod::kGaussSeidel, SolverMethod::kSouthwell,
    SolverMethod::kConjugateGradient};
inline constexpr SolverMethod kAllMethods[] = {
    SolverMethod::kJacobi, SolverMethod::kGaussSeidel, SolverMethod::kSouthwell,
    SolverMethod::kConjugateGradient, SolverMethod::kDirect};

}  // namespace radflux::testing
