// Solving from rows that spilled to disk: jacobi and gauss_seidel stream them back and
// give B bit for bit equal to the in-memory solve; methods that need every row refuse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "solver/solve/energy_balance.h"
#include "solver/sparse/file_block_spill.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

// The Cornell box at ~600 patches, rows in memory and in a store whose budget keeps a
// two 16 KB chunks in memory and spills the rest; both averaged by reciprocity
// (reciprocal_pairs.h: the store's in passes of two chunks, the averaged rows all spilled).
class SpilledCornell : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    absl::StatusOr<Scene> scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    JobOptions options;
    options.mesh.target_patches = 600;
    absl::StatusOr<std::unique_ptr<PreparedJob>> job = PrepareJob(*std::move(scene), options);
    ASSERT_TRUE(job.ok()) << job.status();
    job_ = job->release();
    absl::StatusOr<FormFactorResult> rows = BuildFormFactors(job_->rows, options.form_factors);
    ASSERT_TRUE(rows.ok()) << rows.status();
    matrix_ = new CsrMatrix(std::move(rows->matrix));
    absl::StatusOr<RowBuildSummary> built = BuildFormFactorsInto(
        job_->rows, options.form_factors,
        std::make_unique<RowStore>(matrix_->rows, 32 << 10, std::make_unique<FileBlockSpill>(""),
                                   16 << 10),
        "");
    ASSERT_TRUE(built.ok()) << built.status();
    store_ = built->store.release();
  }
  static void TearDownTestSuite() {
    delete store_;
    delete matrix_;
    delete job_;
  }
  static RadiositySystem InMemory() { return {matrix_, &job_->attributes, nullptr}; }
  static RadiositySystem Spilled() { return {nullptr, &job_->attributes, store_}; }

  static SolveResult SolveWith(const RadiositySystem& system, SolverMethod method) {
    SolverOptions options;
    options.method = method;
    options.tolerance = 1e-7;
    absl::StatusOr<SolveResult> result = Solve(system, options);
    EXPECT_TRUE(result.ok()) << result.status();
    return result.ok() ? *std::move(result) : SolveResult{};
  }

  static void ExpectSameSolve(SolverMethod method) {
    const SolveResult memory = SolveWith(InMemory(), method);
    const SolveResult spilled = SolveWith(Spilled(), method);
    EXPECT_TRUE(memory.converged);
    EXPECT_GT(memory.iterations, 3);
    EXPECT_EQ(spilled.method, method);
    EXPECT_EQ(spilled.iterations, memory.iterations);
    EXPECT_EQ(spilled.residual_history, memory.residual_history);  // exact doubles
    EXPECT_EQ(spilled.residual, memory.residual);
    ASSERT_EQ(spilled.radiosity.size(), memory.radiosity.size());
    size_t differing = 0;
    for (size_t i = 0; i < memory.radiosity.size(); ++i)
      differing += spilled.radiosity[i] != memory.radiosity[i];
    EXPECT_EQ(differing, 0u);
  }

  static PreparedJob* job_;
  static CsrMatrix* matrix_;
  static RowStore* store_;
};
PreparedJob* SpilledCornell::job_ = nullptr;
CsrMatrix* SpilledCornell::matrix_ = nullptr;
RowStore* SpilledCornell::store_ = nullptr;

TEST_F(SpilledCornell, MostRowsSpillAndComeBackUnchanged) {
  EXPECT_EQ(store_->nnz(), matrix_->nnz());
  // Each chunk has its own leading row offset: 8 bytes more per chunk.
  EXPECT_NEAR(static_cast<double>(store_->Bytes()), static_cast<double>(matrix_->Bytes()), 1024);
  EXPECT_LE(store_->MemoryBytes(), 32u << 10);
  EXPECT_GT(store_->SpilledBytes(), 3 * store_->MemoryBytes());
  uint32_t next = 0;
  size_t mismatched_rows = 0;
  const absl::Status s = store_->ForEach([&](const RowsView& rows) {
    EXPECT_EQ(rows.first_row, next);
    for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
      const auto c = rows.RowCols(i), ec = matrix_->RowCols(i);
      const auto v = rows.RowValues(i), ev = matrix_->RowValues(i);
      mismatched_rows += !std::equal(c.begin(), c.end(), ec.begin(), ec.end()) ||
                         !std::equal(v.begin(), v.end(), ev.begin(), ev.end());
    }
    next = rows.EndRow();
  });
  ASSERT_TRUE(s.ok()) << s;
  EXPECT_EQ(next, matrix_->rows);
  EXPECT_EQ(mismatched_rows, 0u);
}

// The rows compared above are averaged by reciprocity, in memory and spilled: against the rows
// as built (no averaging) most rows changed, each keeping its own rays' sum.
TEST_F(SpilledCornell, TheRowsAreAveragedByReciprocity) {
  FormFactorOptions options;
  options.reciprocal_pairs = false;
  const absl::StatusOr<FormFactorResult> raw = BuildFormFactors(job_->rows, options);
  ASSERT_TRUE(raw.ok()) << raw.status();
  ASSERT_EQ(raw->matrix.rows, matrix_->rows);
  uint32_t changed = 0;
  double worst_sum = 0;
  for (uint32_t i = 0; i < matrix_->rows; ++i) {
    const auto c = matrix_->RowCols(i), rc = raw->matrix.RowCols(i);
    const auto v = matrix_->RowValues(i), rv = raw->matrix.RowValues(i);
    changed += !std::equal(c.begin(), c.end(), rc.begin(), rc.end()) ||
               !std::equal(v.begin(), v.end(), rv.begin(), rv.end());
    worst_sum = std::max(worst_sum, std::abs(matrix_->RowSum(i) - raw->matrix.RowSum(i)));
  }
  EXPECT_GT(changed, matrix_->rows * 9 / 10);
  EXPECT_LT(worst_sum, 1e-5);
}

TEST_F(SpilledCornell, JacobiIsBitIdentical) { ExpectSameSolve(SolverMethod::kJacobi); }

TEST_F(SpilledCornell, GaussSeidelIsBitIdentical) { ExpectSameSolve(SolverMethod::kGaussSeidel); }

TEST_F(SpilledCornell, AutoPicksGaussSeidel) {
  EXPECT_EQ(ResolveSolver(Spilled(), SolverMethod::kAuto), SolverMethod::kGaussSeidel);
  EXPECT_EQ(SolveWith(Spilled(), SolverMethod::kAuto).method, SolverMethod::kGaussSeidel);
}

TEST_F(SpilledCornell, MethodsNeedingEveryRowAreRefused) {
  for (SolverMethod method :
       {SolverMethod::kConjugateGradient, SolverMethod::kSouthwell, SolverMethod::kDirect}) {
    SolverOptions options;
    options.method = method;
    const absl::StatusOr<SolveResult> result = Solve(Spilled(), options);
    EXPECT_EQ(result.status().code(), absl::StatusCode::kFailedPrecondition) << SolverName(method);
    EXPECT_NE(result.status().message().find("needs every form-factor row in memory"),
              std::string::npos)
        << result.status();
  }
}

TEST_F(SpilledCornell, EnergyBalanceStreamsToTheSameNumbers) {
  const SolveResult solved = SolveWith(InMemory(), SolverMethod::kGaussSeidel);
  const FormFactorOptions rows;  // the defaults the rows were built with
  const RowSampling sampling{SampledRays(rows), LightSamplesPerRow(rows)};
  const EnergyBalance memory = ComputeEnergyBalance(InMemory(), solved.radiosity, sampling);
  const absl::StatusOr<EnergyBalance> spilled =
      StreamEnergyBalance(Spilled(), solved.radiosity, sampling);
  ASSERT_TRUE(spilled.ok()) << spilled.status();
  EXPECT_EQ(spilled->absorbed, memory.absorbed);
  EXPECT_EQ(spilled->escaped, memory.escaped);
  EXPECT_EQ(spilled->noise, memory.noise);
  // Within the rows' own noise (each row's k_i rays and its light samples: a fixed 1% was one
  // draw of an imbalance whose spread over seeds is about 0.5% per band at these 600 patches,
  // seeds 1-3 of the area-proportional rows 1.2% in blue).
  EXPECT_TRUE(memory.Ok()) << memory.RelativeImbalance() << " tolerance " << memory.Tolerance();
}

// RunJob with --memory-limit: the whole pipeline on spilled (and averaged) rows, same B as in
// memory.
TEST(SpillJob, RunJobWithAMemoryLimitMatchesTheInMemoryJob) {
  absl::StatusOr<Scene> scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok()) << scene.status();
  JobOptions options;
  options.mesh.target_patches = 300;
  options.solver.method = SolverMethod::kAuto;
  const absl::StatusOr<JobResult> memory = RunJob(*scene, options);
  ASSERT_TRUE(memory.ok()) << memory.status();
  options.spill.memory_limit = 1;  // every chunk spills
  const absl::StatusOr<JobResult> spilled = RunJob(*scene, options);
  ASSERT_TRUE(spilled.ok()) << spilled.status();
  ASSERT_NE(spilled->row_store, nullptr);
  EXPECT_EQ(spilled->row_store->SpilledBytes(), memory->form_factors.Bytes());
  EXPECT_EQ(spilled->RowNonZeros(), memory->RowNonZeros());
  EXPECT_EQ(spilled->solve.method, SolverMethod::kGaussSeidel);
  EXPECT_EQ(spilled->solve.radiosity, memory->solve.radiosity);
}

// The estimate counts the rows' budget (plus the chunks in flight and the reciprocity
// averaging's two) instead of all rows twice (rows and cg's symmetric copy).
TEST(SpillJob, EstimateCountsAtMostTheBudgetForRows) {
  absl::StatusOr<Scene> scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok()) << scene.status();
  JobOptions options;
  options.mesh.target_patches = 100000;
  const uint64_t n = SubdivideScene(*scene, options.mesh)->size();
  const uint64_t rows = n * (options.form_factors.rays + 64) * 8;  // bytes of all rows
  const uint64_t in_memory = EstimateJobBytes(*scene, options);
  options.spill.memory_limit = 16 << 20;
  const uint64_t spilling = EstimateJobBytes(*scene, options);
  EXPECT_EQ(in_memory - spilling, 2 * rows - ((16 << 20) + (kRowReadAhead + 4) * kRowChunkBytes));
}

TEST(SpillJob, OptionsThatCannotStreamAreRefusedUpFront) {
  JobOptions options;
  options.spill.memory_limit = 1 << 20;
  options.solver.method = SolverMethod::kConjugateGradient;
  absl::Status s = ValidateJobOptions(options);
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("solver cg needs them all in memory"), std::string::npos) << s;
  options = JobOptions{};
  options.spill.directory = "/tmp";
  EXPECT_EQ(ValidateJobOptions(options).code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace radflux
