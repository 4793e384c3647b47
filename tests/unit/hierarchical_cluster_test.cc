// Clustering in hierarchical radiosity: on a room with a grid of n x n cubes (6 n^2 + 7 faces)
// the solve starts from one link whatever n, its links per leaf grow far slower than the
// faces, and its object means agree with a uniform analytic solve; tessellated plates and a
// tessellated furnace cube (so that clusters stand above many faces) still meet the closed
// forms at the tolerances of hierarchical_closed_form_test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "hierarchical_test_scenes.h"
#include "howell_closed_forms.h"
#include "solver/hierarchical/hierarchical.h"
#include "solver/pipeline.h"

namespace radflux {
namespace {

using testing::GatheredFormFactor;
using testing::ObjectMean;
using testing::SolvedHierarchical;

// Links per leaf at n = 4, 8, 16 (103, 391, 1543 faces; the roots are 7 more: the light hung
// 1% of its size under the ceiling hides the ceiling there, which is cut into 8 pieces
// around it): one initial link and roots - 1 clusters at every size; links per leaf grow at
// most like faces^0.5 from the smallest to the largest (measured: 5.4, 7.5, 15.0 links per
// leaf, exponent 0.39; without clusters the initial links alone grow like faces^2).
TEST(HierarchicalClusters, LinksPerLeafGrowFarSlowerThanFaces) {
  std::vector<double> faces, per_leaf;
  for (int n : {4, 8, 16}) {
    const Scene scene = testing::CubeGridRoom(n);
    const HierarchicalResult r = SolvedHierarchical(scene, 1e-4, 4);
    std::printf("n=%d: %zu faces, %zu clusters, %zu initial links, %zu links, %zu leaves\n", n,
                r.stats.roots, r.stats.clusters, r.stats.initial_links, r.stats.links,
                r.stats.leaves);
    EXPECT_EQ(r.stats.roots, 6u * n * n + 7 + 7);
    EXPECT_EQ(r.stats.clusters, r.stats.roots - 1);
    EXPECT_EQ(r.stats.initial_links, 1u);
    faces.push_back(static_cast<double>(r.stats.roots));
    per_leaf.push_back(static_cast<double>(r.stats.links) / r.stats.leaves);
  }
  const double exponent = std::log(per_leaf[2] / per_leaf[0]) / std::log(faces[2] / faces[0]);
  std::printf("links per leaf grow like faces^%.2f\n", exponent);
  EXPECT_LT(exponent, 0.5);
}

// No link joins two nodes that share a face (so none joins a cluster to its own descendant,
// nor an element to a cluster holding it): every link's ends cover disjoint ranges of the
// cluster order (ClusterTree::Build of the same faces gives the solver's clusters).
TEST(HierarchicalClusters, NoLinkJoinsOverlappingNodes) {
  const Scene scene = testing::CubeGridRoom(4);
  const HierarchicalResult r = SolvedHierarchical(scene, 1e-4, 4);
  const ClusterTree clusters = ClusterTree::Build(r.tree);
  std::vector<uint32_t> position(clusters.order.size());
  for (uint32_t k = 0; k < clusters.order.size(); ++k) position[clusters.order[k]] = k;
  auto range = [&](uint32_t node) -> std::pair<uint32_t, uint32_t> {
    if (IsCluster(node)) {
      const Cluster& c = clusters.clusters[ClusterIndex(node)];
      return {c.begin, c.end};
    }
    while (r.tree.nodes[node].parent != kNoElement) node = r.tree.nodes[node].parent;
    return {position[node], position[node] + 1};
  };
  size_t with_cluster = 0;
  for (size_t s = 0; s < r.links.Slots(); ++s) {
    const uint32_t p = r.links.Receiver(s);
    for (uint64_t k = r.links.begin[s]; k < r.links.begin[s + 1]; ++k) {
      const uint32_t q = r.links.source[k];
      const auto [pb, pe] = range(p);
      const auto [qb, qe] = range(q);
      EXPECT_TRUE(pe <= qb || qe <= pb) << p << " <- " << q;
      with_cluster += IsCluster(p) || IsCluster(q);
    }
  }
  std::printf("%zu links, %zu with a cluster end\n", r.links.size(), with_cluster);
  EXPECT_GT(with_cluster, 0u);
}

// Object means of the cube room (n = 4) with clusters against a uniform analytic solve on
// about 2000 patches, and against the hierarchical solve without clusters.
TEST(HierarchicalClusters, CubeRoomAgreesWithUniformAnalyticSolve) {
  const Scene scene = testing::CubeGridRoom(4);
  JobOptions job;
  job.mesh.target_patches = 2000;
  job.form_factors.method = FormFactorMethod::kAnalytic;
  job.solver.tolerance = 1e-7;
  absl::StatusOr<JobResult> uniform = RunJob(scene, job);
  ASSERT_TRUE(uniform.ok()) << uniform.status();
  const HierarchicalResult on = SolvedHierarchical(scene, 1e-4, 4, /*clusters=*/true);
  const HierarchicalResult off = SolvedHierarchical(scene, 1e-4, 4, /*clusters=*/false);
  for (const char* object : {"room", "cubes"}) {
    const double ref = ObjectMean(scene, uniform->job->mesh, uniform->solve.radiosity, object);
    const double with = ObjectMean(scene, on.mesh, on.solve.radiosity, object);
    const double without = ObjectMean(scene, off.mesh, off.solve.radiosity, object);
    std::printf("%s: uniform %.5f clusters on %.5f (%+.2f%%) off %.5f (%+.2f%%)\n", object, ref,
                with, 100 * (with / ref - 1), without, 100 * (without / ref - 1));
    EXPECT_NEAR(with / ref, 1, 0.03) << object;
  }
}

// Each plate as 8 x 8 faces: the gathered F still meets Howell's closed forms.
TEST(HierarchicalClusters, TessellatedPlatesMeetClosedForms) {
  for (double d : {0.5, 1.0, 2.0}) {
    int next = 1;
    std::string obj = testing::TessellatedQuad(
        "a", "white", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, 8, next);
    obj += testing::TessellatedQuad(
        "b", "lamp", {{-.5, -.5, d}, {-.5, .5, d}, {.5, .5, d}, {.5, -.5, d}}, 8, next);
    const Scene scene = testing::SceneFromObj(obj, testing::kPlateMtl);
    const HierarchicalResult r = SolvedHierarchical(scene, 1e-4, 16);
    const double f = GatheredFormFactor(scene, r);
    const double exact = testing::ParallelRectangles(1, 1, d);
    std::printf("tessellated parallel d=%g: exact %.6f clustered %.6f (%zu clusters, %zu links)\n",
                d, exact, f, r.stats.clusters, r.stats.links);
    EXPECT_EQ(r.stats.clusters, 127u);
    EXPECT_NEAR(f, exact, 0.002) << "d=" << d;
  }
  int next = 1;
  std::string obj = testing::TessellatedQuad(
      "a", "white", {{0, 0, 0}, {1, 0, 0}, {1, 1.3, 0}, {0, 1.3, 0}}, 8, next);
  obj += testing::TessellatedQuad("b", "lamp", {{0, 0, 0}, {0, 1.3, 0}, {0, 1.3, 0.7}, {0, 0, 0.7}},
                                  8, next);
  const Scene scene = testing::SceneFromObj(obj, testing::kPlateMtl);
  const HierarchicalResult r = SolvedHierarchical(scene, 1e-4, 16);
  const double f = GatheredFormFactor(scene, r);
  const double exact = testing::PerpendicularRectangles(1, 0.7, 1.3);
  std::printf("tessellated perpendicular: exact %.6f clustered %.6f (%zu links)\n", exact, f,
              r.stats.links);
  EXPECT_NEAR(f, exact, 0.004);
}

// The furnace cube with each side as 4 x 4 faces: B = E / (1 - rho) = 2 pi. Its mean meets
// the untessellated test's 0.003; its RMS (4.9e-2, set by the element links between the
// faces, as without clusters) may exceed that without clusters by at most 10%.
TEST(HierarchicalClusters, TessellatedFurnaceCube) {
  int next = 1;
  const std::vector<std::vector<Vec3>> sides = {
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{1, 1, 0}, {0, 1, 0}, {0, 1, 1}, {1, 1, 1}},
      {{0, 1, 0}, {0, 0, 0}, {0, 0, 1}, {0, 1, 1}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
  std::string obj;
  for (auto side : sides) {
    std::reverse(side.begin(), side.end());  // inward
    obj += testing::TessellatedQuad("box", "hot", side, 4, next);
  }
  const Scene scene = testing::SceneFromObj(obj, "newmtl hot\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  const double exact = std::numbers::pi / (1 - 0.5);
  const HierarchicalResult on = SolvedHierarchical(scene, 1e-3, 16, /*clusters=*/true);
  const HierarchicalResult off = SolvedHierarchical(scene, 1e-3, 16, /*clusters=*/false);
  const auto [rms_on, mean_on] = testing::LeafRelativeError(on, exact);
  const auto [rms_off, mean_off] = testing::LeafRelativeError(off, exact);
  std::printf(
      "tessellated furnace: clusters on rms %.2e mean %.2e (%zu clusters, %zu links); "
      "off rms %.2e mean %.2e (%zu links)\n",
      rms_on, mean_on, on.stats.clusters, on.stats.links, rms_off, mean_off, off.stats.links);
  EXPECT_EQ(on.stats.clusters, 95u);
  EXPECT_LT(rms_on, 1.1 * rms_off);
  EXPECT_LT(std::abs(mean_on), 0.003);
}

}  // namespace
}  // namespace radflux
