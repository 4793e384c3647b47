// A Monte Carlo row depends only on (mesh, options, seed, i) (row_builder.h): never on the
// thread that builds it nor on the rows that thread built before. Workers build blocks in
// order on their own threads and the server rebuilds single rows on another to check them
// (server/workers/row_check.h), so both must give the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <thread>
#include <vector>

#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

// Whether row i of blocks a and b has the same columns and the same bits.
bool SameRow(const RowBlock& a, const RowBlock& b, uint32_t i) {
  const auto ca = a.View().RowCols(i), cb = b.View().RowCols(i);
  const auto va = a.View().RowValues(i), vb = b.View().RowValues(i);
  return ca.size() == cb.size() && std::equal(ca.begin(), ca.end(), cb.begin()) &&
         (va.empty() || std::memcmp(va.data(), vb.data(), va.size() * sizeof(float)) == 0);
}

TEST(RowThreadIndependence, RowsRebuiltAloneOnAnotherThreadAreBitIdentical) {
  absl::StatusOr<Scene> scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  ASSERT_TRUE(scene.ok()) << scene.status();
  JobOptions options;
  options.mesh.target_patches = 600;
  options.form_factors.rays = 128;
  options.form_factors.seed = 11;
  absl::StatusOr<std::unique_ptr<PreparedJob>> job = PrepareJob(*std::move(scene), options);
  ASSERT_TRUE(job.ok()) << job.status();
  const RowContext& context = (*job)->rows;
  const uint32_t n = context.Unknowns();
  const std::unique_ptr<RowBuilder> builder = MakeRowBuilder(context, options.form_factors);
  RowAccumulator row(n);
  RowBlockStats stats;
  const RowBlock all =
      BuildRowBlock(*builder, context, options.form_factors.cutoff, 0, n, row, stats);
  // Another thread rebuilds each row alone, from the last to the first.
  std::vector<uint32_t> differ;
  std::thread([&] {
    RowAccumulator own(n);
    for (uint32_t i = n; i-- > 0;) {
      RowBlockStats s;
      const RowBlock one =
          BuildRowBlock(*builder, context, options.form_factors.cutoff, i, 1, own, s);
      if (!SameRow(all, one, i)) differ.push_back(i);
    }
  }).join();
  EXPECT_TRUE(differ.empty()) << differ.size() << " of " << n << " rows differ, the first "
                              << differ.back();
}

}  // namespace
}  // namespace radflux
