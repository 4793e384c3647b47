// `radflux viewfactors` with a partly transparent surface (issue 19): F_ij to a surface j of
// opacity alpha is the share of what leaves i that j's opaque part intercepts, alpha times
// the geometric factor; the rest passes on to what lies behind j. Rows of a closed
// enclosure still sum to 1, and reciprocity holds with the opaque areas alpha A that the
// outputs write: alpha_i A_i F_ij = alpha_j A_j F_ji. Both integrations agree.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "howell_closed_forms.h"
#include "solver/formfactor/view_factor_job.h"
#include "test_scenes.h"

namespace radflux {
namespace {

// Three coaxial 1 x 1 squares: "a" at z = 0 facing up, "b" at z = 1 facing down at opacity
// 0.5, "c" at z = 2 facing down. Every segment from a to c crosses b.
Scene Stack() {
  int next = 1;
  std::string obj =
      testing::ObjQuad("a", "grey", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  obj += testing::ObjQuad("b", "half", {{-.5, -.5, 1}, {-.5, .5, 1}, {.5, .5, 1}, {.5, -.5, 1}}, next);
  obj += testing::ObjQuad("c", "grey", {{-.5, -.5, 2}, {-.5, .5, 2}, {.5, .5, 2}, {.5, -.5, 2}}, next);
  Scene scene = testing::SceneFromObj(obj, "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl half\nKd 0.5 0.5 0.5\n");
  for (Material& m : scene.materials) {
    if (m.name == "half") m.opacity = 0.5;
  }
  return scene;
}

struct View3dFile {
  std::vector<double> area;
  std::vector<std::vector<double>> f;
};

// The areas and rows of a View3D text output of n surfaces.
View3dFile ReadView3d(const std::string& path, size_t n) {
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  View3dFile file{std::vector<double>(n), std::vector<std::vector<double>>(n, std::vector<double>(n))};
  for (double& a : file.area) in >> a;
  for (auto& row : file.f)
    for (double& v : row) in >> v;
  EXPECT_TRUE(in.good()) << path;
  return file;
}

View3dFile RunStack(ViewFactorIntegration integration) {
  ViewFactorJobOptions options;
  options.integration = integration;
  options.job.form_factors.rays = 1 << 16;
  options.job.mesh.max_edge = 0.25;
  options.surface_rows.threads = options.job.form_factors.threads = 1;
  options.output.format = ViewFactorFormat::kView3d;
  options.output.path = ::testing::TempDir() + "transparency_vf.txt";
  absl::StatusOr<ViewFactorReport> report = RunViewFactorJob(Stack(), options);
  EXPECT_TRUE(report.ok()) << report.status();
  const View3dFile file = ReadView3d(options.output.path, 3);
  std::remove(options.output.path.c_str());
  return file;
}

TEST(ViewFactorTransparency, FactorsToAPartlyTransparentSurfaceAreItsOpaqueShare) {
  const double f1 = testing::ParallelRectangles(1, 1, 1), f2 = testing::ParallelRectangles(1, 1, 2);
  // Adaptive: F_ab is the exact contour integral times 0.5 (to --vf-tolerance); F_ac and F_ca
  // go through b as a blocker, which 0.5 of the pair's 256 visibility segments pass by the
  // hash rule (sigma 0.031 of the pass fraction, 6% of the ratio: 4 sigma is 0.25; without
  // partial transmission the ratio would be 0 or 2). Patch rows: 16 patches a face, 2^16
  // rays each; a to c, sigma about 0.3% of F.
  struct Case {
    ViewFactorIntegration integration;
    const char* name;
    double exact_tolerance, through_tolerance;
  };
  for (const Case& c : {Case{ViewFactorIntegration::kAdaptive, "adaptive", 1e-3, 0.25},
                        Case{ViewFactorIntegration::kPatches, "patches", 0.01, 0.02}}) {
    const View3dFile vf = RunStack(c.integration);
    EXPECT_EQ(vf.area, (std::vector<double>{1, 0.5, 1})) << c.name << ": opaque areas";
    EXPECT_NEAR(vf.f[0][1] / (0.5 * f1), 1, c.exact_tolerance) << c.name << ": a to b";
    EXPECT_NEAR(vf.f[1][0] / f1, 1, c.exact_tolerance) << c.name << ": b to a (opaque)";
    EXPECT_NEAR(vf.f[0][2] / (0.5 * f2), 1, c.through_tolerance) << c.name << ": a to c through b";
    EXPECT_NEAR(vf.f[2][0] / (0.5 * f2), 1, c.through_tolerance) << c.name << ": c to a through b";
    EXPECT_EQ(vf.f[1][2], 0) << c.name << ": c is behind b";
    EXPECT_EQ(vf.f[2][1], 0) << c.name << ": c sees b's back";
    // Reciprocity with the written areas.
    EXPECT_NEAR(vf.area[0] * vf.f[0][1], vf.area[1] * vf.f[1][0], 2e-3 * f1) << c.name;
  }
}

}  // namespace
}  // namespace radflux
