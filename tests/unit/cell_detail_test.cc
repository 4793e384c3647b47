// The cells' detail as the unknowns see it (cell_detail.h) against closed forms: a receiver
// above a group of three cells, one below it, one beside it, one facing away.
#include "solver/formfactor/cell_detail.h"

#include <gtest/gtest.h>

#include <span>
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

// The cells' own indirect light: a receiver at z = 1 facing down (B = 1, 2, 0 per band) over
// "below" (z = 0, facing up), grouped with "away" (x in [3, 4], z = 0, facing down, seeing
// nothing). "below" reads I = F B_r (F = 0.19982, parallel squares 1 apart), "away" 0; with
// rho 0.5, delta_below = rho (I - I/2) and the receiver's H = F delta_below. With "away"
// facing up inside a closed box whose faces face out (a part enclosed in a solid:
// exposed_area.h), every ray of "away" meets a back side and none counts: no indirect detail.
TEST(CellDetail, EachCellTakesItsOwnIndirectLightUnlessEnclosed) {
  for (const bool lid : {false, true}) {
    int next = 1;
    std::string obj;
    obj += ObjQuad("receiver", "white", {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, next);
    obj += ObjQuad("below", "white", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, next);
    obj += lid ? ObjQuad("away", "white", {{3, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}}, next)
               : ObjQuad("away", "white", {{3, 0, 0}, {3, 1, 0}, {4, 1, 0}, {4, 0, 0}}, next);
    if (lid) {  // the box [2.5, 4.5] x [-0.5, 1.5] x [-0.5, 1.5], its faces facing out
      const auto at = [](double x, double y, double z) {
        return Vec3{2.5 + 2 * x, -0.5 + 2 * y, -0.5 + 2 * z};
      };
      const Vec3 v0 = at(0, 0, 0), v1 = at(1, 0, 0), v2 = at(1, 1, 0), v3 = at(0, 1, 0);
      const Vec3 v4 = at(0, 0, 1), v5 = at(1, 0, 1), v6 = at(1, 1, 1), v7 = at(0, 1, 1);
      for (const std::vector<Vec3>& face : std::vector<std::vector<Vec3>>{{v3, v2, v1, v0},
                                                                          {v1, v5, v4, v0},
                                                                          {v2, v6, v5, v1},
                                                                          {v3, v7, v6, v2},
                                                                          {v0, v4, v7, v3},
                                                                          {v5, v6, v7, v4}}) {
        obj += ObjQuad("lid", "white", face, next);
      }
    }
    RowFixture f(SceneFromObj(obj), MeshOptions{lid ? 9 : 3, 0});
    std::vector<uint32_t> unknown(f.mesh.size()), cell(f.mesh.size());
    for (uint32_t p = 0; p < f.mesh.size(); ++p) {
      const std::string& name = f.ObjectOf(p);
      unknown[p] = name == "receiver" ? 0 : name == "lid" ? 2 : 1;
      cell[p] = name == "receiver" ? 0 : name == "below" ? 1 : name == "away" ? 2 : 3;
    }
    const PatchClusters clusters = ClustersFromAssignment(f.mesh, unknown, lid ? 3 : 2);
    const PatchClusters cells = ClustersFromAssignment(f.mesh, cell, lid ? 4 : 3);
    const PatchAttributes attributes = ComputeClusterAttributes(f.scene, f.mesh, clusters);
    const RowContext context = MakeRowContext(f.mesh, attributes, *f.caster, &clusters, &cells);
    const std::vector<Rgb> deviation(cells.size(), Rgb{});  // no direct detail at all
    const std::vector<Rgb> b = {{1, 2, 0}, {0, 0, 0}, {0, 0, 0}};
    const std::vector<Rgb> rho(3, Rgb{0.5, 0.5, 0.5});
    const SolvedLight solved{std::span<const Rgb>(b).first(clusters.size()),
                             std::span<const Rgb>(rho).first(clusters.size())};
    FormFactorOptions options;
    options.rays = 65536;
    const CellDetail detail = GatherCellDetail(context, deviation, options, &solved);
    const double f_below = testing::ParallelRectangles(1, 1, 1);  // 0.19982
    for (int band = 0; band < kBands; ++band) {
      const double expected = lid ? 0 : f_below * 0.5 * (f_below * b[0][band] / 2);
      EXPECT_NEAR(detail.irradiance[0][band], expected, 0.04 * f_below * 0.5 * f_below)
          << (lid ? "lid" : "open") << " band " << band;
    }
    EXPECT_EQ(detail.indirect_cells, lid ? 1u : 2u);
    // What the outputs add to each cell's patches (cell_direct.h's push-down): +- rho F B_r / 2
    // on "below" and "away" (equal areas), 0 on the receiver's own cell.
    ASSERT_EQ(detail.indirect.size(), cells.size());
    for (int band = 0; band < kBands; ++band) {
      const double half = lid ? 0 : 0.5 * f_below * b[0][band] / 2;
      EXPECT_NEAR(detail.indirect[1][band], half, 0.04 * 0.5 * f_below) << band;
      EXPECT_NEAR(detail.indirect[2][band], -half, 0.04 * 0.5 * f_below) << band;
      EXPECT_EQ(detail.indirect[0][band], 0.0);
    }
    // Without the solve's light there is no indirect detail: exactly the direct one (0).
    EXPECT_EQ(GatherCellDetail(context, deviation, options).irradiance[0][0], 0.0);
  }
}

}  // namespace
}  // namespace radflux
