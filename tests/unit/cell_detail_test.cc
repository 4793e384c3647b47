// The cells' detail as the unknowns see it (cell_detail.h) against closed forms: a receiver
// above a group of three cells, one below it, one beside it, one facing away.
#include "solver/formfactor/cell_detail.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "howell_closed_forms.h"
#include "test_scenes.h"

namespace radflux {
namespace {

using testing::ObjQuad;
using testing::RowFixture;
using testing::SceneFromObj;

// A unit square "receiver" at z = 1 facing down; one group of three unit squares, each a
// cell: "below" at z = 0 facing up, "beside" in the plane x = 1 facing -x (sharing an edge
// with both), and "away" at x in [3, 4], z = 0, facing down, whose front nothing sees.
TEST(CellDetail, EachCellWeighsItsDeviationByTheFormFactorToIt) {
  int next = 1;
  std::string obj;
  obj += ObjQuad("receiver", "white", {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, next);
  obj += ObjQuad("below", "white", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, next);
  obj += ObjQuad("beside", "white", {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}}, next);
  obj += ObjQuad("away", "white", {{3, 0, 0}, {3, 1, 0}, {4, 1, 0}, {4, 0, 0}}, next);
  RowFixture f(SceneFromObj(obj), MeshOptions{4, 0});
  const std::vector<std::string> cell_names = {"receiver", "below", "beside", "away"};
  std::vector<uint32_t> unknown(f.mesh.size()), cell(f.mesh.size());
  for (uint32_t p = 0; p < f.mesh.size(); ++p) {
    const std::string& name = f.ObjectOf(p);
    cell[p] = static_cast<uint32_t>(std::find(cell_names.begin(), cell_names.end(), name) -
                                    cell_names.begin());
    unknown[p] = name == "receiver" ? 0 : 1;
  }
  const PatchClusters clusters = ClustersFromAssignment(f.mesh, unknown, 2);
  const PatchClusters cells = ClustersFromAssignment(f.mesh, cell, 4);
  const PatchAttributes attributes = ComputeClusterAttributes(f.scene, f.mesh, clusters);
  const RowContext context = MakeRowContext(f.mesh, attributes, *f.caster, &clusters, &cells);
  // Deviations per band, the group's summing to 0 over its cells' areas.
  const std::vector<Rgb> deviation = {{0, 0, 0}, {1, 2, 0}, {-2, -1, 0}, {1, -1, 0}};
  FormFactorOptions options;
  options.rays = 65536;  // the receiver casts 32,768 (its area against the mean row's, 2)
  const CellDetail detail = GatherCellDetail(context, deviation, options);

  const double below = testing::ParallelRectangles(1, 1, 1);        // 0.19982
  const double beside = testing::PerpendicularRectangles(1, 1, 1);  // 0.20004
  const Rgb receiver = detail.irradiance[0], group = detail.irradiance[1];
  for (int b = 0; b < kBands; ++b) {
    // The receiver sees "below" and "beside", each with its own form factor.
    const double expected = below * deviation[1][b] + beside * deviation[2][b];
    EXPECT_NEAR(receiver[b], expected, 0.01) << "band " << b;
    // The group sees itself: a third of its rays leave "below" towards "beside", a third
    // "beside" towards "below"; "away" sees nothing.
    const double own = (beside * deviation[2][b] + beside * deviation[1][b]) / 3;
    EXPECT_NEAR(group[b], own, 0.01) << "band " << b;
  }
  EXPECT_EQ(receiver[2], 0.0);  // no deviation, no detail: exactly
  EXPECT_GT(detail.rays, 32768u);
}

}  // namespace
}  // namespace radflux
