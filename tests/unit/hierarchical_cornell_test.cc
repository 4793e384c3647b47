// Refining further never increases the error on the Cornell box: hierarchical at three
// link epsilons against a finer hierarchical solve, and adaptive at three pass counts against
// an independent fine Monte Carlo solve; error = RMS over scene objects of the relative error
// of the object's area-weighted mean B (a measure that works across different meshes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "solver/adaptive/adaptive_refine.h"
#include "solver/hierarchical/hierarchical.h"
#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

std::map<std::string, double> ObjectMeans(const Scene& scene, const PatchMesh& mesh,
                                          const std::vector<Rgb>& b) {
  std::map<std::string, double> sum, area;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const std::string& o = scene.objects[scene.faces[mesh.patches[p].face].object];
    sum[o] += mesh.patches[p].area * (b[p][0] + b[p][1] + b[p][2]);
    area[o] += mesh.patches[p].area;
  }
  for (auto& [o, s] : sum) s /= area[o];
  return sum;
}

double Error(const std::map<std::string, double>& run, const std::map<std::string, double>& ref) {
  double sq = 0;
  for (const auto& [o, r] : ref) {
    if (o == "light") continue;
    const double e = run.at(o) / r - 1;
    sq += e * e;
  }
  return std::sqrt(sq / (ref.size() - 1));
}

class CornellRefinement : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(*LoadObjFile(testing::SourcePath("scenes/cornell_box.obj")));
    const HierarchicalResult r = Hierarchical(3e-5);
    reference_ = new std::map<std::string, double>(ObjectMeans(*scene_, r.mesh, r.solve.radiosity));
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete reference_;
  }
  static HierarchicalResult Hierarchical(double epsilon, double min_area_fraction = 2e-5) {
    HierarchicalOptions h;
    h.link_epsilon = epsilon;
    h.min_area_fraction = min_area_fraction;
    SolverOptions s;
    s.tolerance = 1e-7;
    return *SolveHierarchical(*scene_, h, s);
  }
  static Scene* scene_;
  static std::map<std::string, double>* reference_;
};
Scene* CornellRefinement::scene_ = nullptr;
std::map<std::string, double>* CornellRefinement::reference_ = nullptr;

TEST_F(CornellRefinement, HierarchicalErrorNeverIncreasesOverThreeEpsilons) {
  std::vector<double> errors;
  for (double eps : {1e-3, 3e-4, 1e-4}) {
    const HierarchicalResult r = Hierarchical(eps);
    errors.push_back(Error(ObjectMeans(*scene_, r.mesh, r.solve.radiosity), *reference_));
    std::printf("hierarchical eps %g: %zu leaves %zu links error %.3e\n", eps, r.stats.leaves,
                r.stats.links, errors.back());
  }
  EXPECT_LE(errors[1], errors[0]);
  EXPECT_LE(errors[2], errors[1]);
}

// `--min-element-area`: no leaf made by refinement is smaller than the floor (a fraction of
// the scene's area; a root may be: contact meshing cuts the floor's roots along the blocks'
// feet), and a 4x lower floor, at an epsilon the floor binds, gives more and smaller leaves.
TEST_F(CornellRefinement, ElementFloorBoundsTheSmallestLeaf) {
  std::vector<size_t> leaves;
  std::vector<double> smallest;
  for (double floor : {1e-3, 2.5e-4}) {
    const HierarchicalResult r = Hierarchical(1e-5, floor);
    double scene_area = 0;  // the conforming mesh covers every face once
    for (const Patch& p : r.mesh.patches) scene_area += p.area;
    double least = scene_area;
    for (uint32_t l : r.leaves) {
      if (r.tree.nodes[l].parent != kNoElement) least = std::min(least, r.tree.nodes[l].area);
    }
    EXPECT_GE(least, floor * scene_area * (1 - 1e-9)) << "floor " << floor;
    leaves.push_back(r.leaves.size());
    smallest.push_back(least);
  }
  EXPECT_GT(leaves[1], leaves[0]);
  EXPECT_LT(smallest[1], smallest[0]);
}

// The reference for adaptive meshing: Monte Carlo rows on 2,000 patches, k = 1024, 256 light
// samples per row (object means within ~0.5% of Cycles at k = 64). Not the hierarchical
// reference above: it converges to object means 0.5-3% below this one (the ceiling -3.1%),
// more than the adaptive errors measured here.
std::map<std::string, double> MonteCarloReference(const Scene& scene) {
  JobOptions options;
  options.mesh.target_patches = 2000;
  options.form_factors.rays = 1024;
  options.form_factors.samples = 16;
  options.solver.tolerance = 1e-7;
  const JobResult r = *RunJob(scene, options);
  return ObjectMeans(scene, r.job->mesh, r.solve.radiosity);
}

// 32 points per patch: refinement never splits a patch whose B is flat (the short block's top
// stays one patch at every pass), so its quadrature error stays whatever the first pass made
// it. At the default 4 points that alone is up to +-10% on that face, more than what
// refinement changes elsewhere.
TEST_F(CornellRefinement, AdaptiveErrorNeverIncreasesOverThreePasses) {
  const std::map<std::string, double> reference = MonteCarloReference(*scene_);
  std::vector<double> errors;
  for (int passes : {0, 1, 2}) {
    MeshOptions mesh;
    mesh.target_patches = 100;
    FormFactorOptions ff;
    ff.method = FormFactorMethod::kAnalytic;
    ff.samples = 32;
    SolverOptions s;
    s.tolerance = 1e-7;
    AdaptiveOptions a;
    a.passes = passes;
    a.threshold = 0.3;
    const AdaptiveResult r = *SolveAdaptive(*scene_, mesh, ff, s, a);
    errors.push_back(Error(ObjectMeans(*scene_, r.leaf_mesh, r.leaf_radiosity), reference));
    std::printf("adaptive passes %d: %zu patches error %.3e\n", passes, r.leaves.size(),
                errors.back());
  }
  EXPECT_LE(errors[1], errors[0]);
  EXPECT_LE(errors[2], errors[1]);
}

}  // namespace
}  // namespace radflux
