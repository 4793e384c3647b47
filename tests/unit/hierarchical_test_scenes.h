// Scenes and helpers shared by the hierarchical and adaptive tests: two-plate scenes where
// one plate emits (rho 0) and the other reflects, so the receiver's mean B is rho * E * F.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "solver/hierarchical/hierarchical.h"
#include "solver/mesh/patch_mesh.h"
#include "test_scenes.h"

namespace radflux::testing {

// Emitter "lamp" (rho 0, Ke 1 so E = pi) and receiver "white" (rho 0.5).
inline const char* kPlateMtl =
    "newmtl white\nKd 0.5 0.5 0.5\n"
    "newmtl lamp\nKd 0 0 0\nKe 1 1 1\n";

// Receiver "a" at z=0 facing +z, emitter "b" at z=d facing -z, both 1 x 1.
inline Scene EmittingParallelSquares(double d) {
  int next = 1;
  std::string obj =
      ObjQuad("a", "white", {{-.5, -.5, 0}, {.5, -.5, 0}, {.5, .5, 0}, {-.5, .5, 0}}, next);
  obj += ObjQuad("b", "lamp", {{-.5, -.5, d}, {-.5, .5, d}, {.5, .5, d}, {.5, -.5, d}}, next);
  return SceneFromObj(obj, kPlateMtl);
}

// Receiver floor "a" (w along x, l along y), emitting wall "b" (h along z), sharing x=0.
inline Scene EmittingPerpendicularPlates(double w, double h, double l) {
  int next = 1;
  std::string obj = ObjQuad("a", "white", {{0, 0, 0}, {w, 0, 0}, {w, l, 0}, {0, l, 0}}, next);
  obj += ObjQuad("b", "lamp", {{0, 0, 0}, {0, l, 0}, {0, l, h}, {0, 0, h}}, next);
  return SceneFromObj(obj, kPlateMtl);
}

// Unit cube, every face inward, rho 0.5 and E = pi everywhere: B = pi / (1 - 0.5).
inline Scene FurnaceCube() {
  return SceneFromObj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "usemtl white\n"
      "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n",
      "newmtl white\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
}

// The quad with corners v (counter-clockwise from the front) as an n x n grid of OBJ faces.
inline std::string TessellatedQuad(const std::string& object, const std::string& material,
                                   const std::vector<Vec3>& v, int n, int& next) {
  auto at = [&](double u, double w) {
    return v[0] * ((1 - u) * (1 - w)) + v[1] * (u * (1 - w)) + v[2] * (u * w) +
           v[3] * ((1 - u) * w);
  };
  std::string obj;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u0 = double(i) / n, u1 = double(i + 1) / n;
      const double w0 = double(j) / n, w1 = double(j + 1) / n;
      obj += ObjQuad(object, material, {at(u0, w0), at(u1, w0), at(u1, w1), at(u0, w1)}, next);
    }
  }
  return obj;
}

// The six faces of the box [lo, hi] (inward: seen from inside) as OBJ quads.
inline std::string ObjBox(const std::string& object, const std::string& material, Vec3 lo, Vec3 hi,
                          bool inward, int& next) {
  const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  std::vector<std::vector<Vec3>> faces = {{{x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0}},
                                          {{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}},
                                          {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}},
                                          {{x1, y1, z0}, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}},
                                          {{x0, y1, z0}, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}},
                                          {{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}};
  std::string obj;
  for (auto& f : faces) {
    if (inward) std::reverse(f.begin(), f.end());
    obj += ObjQuad(object, material, f, next);
  }
  return obj;
}

// The many-faces scene of the clustering tests (bench/cube_grid_scene.py writes the same as
// OBJ): a 4 x 4 x 2 room ("room", rho 0.5, faces inward), a 1 x 1 lamp under the ceiling's
// centre ("light", E = pi), and an n x n grid of closed floating cubes ("cubes", rho 0.5)
// over [0.5, 3.5]^2, each 1.5 / n on a side, from z = 0.25: 6 n^2 + 7 faces.
inline Scene CubeGridRoom(int n) {
  int next = 1;
  std::string obj = ObjBox("room", "white", {0, 0, 0}, {4, 4, 2}, /*inward=*/true, next);
  obj += ObjQuad("light", "lamp",
                 {{1.5, 1.5, 1.99}, {1.5, 2.5, 1.99}, {2.5, 2.5, 1.99}, {2.5, 1.5, 1.99}}, next);
  const double cell = 3.0 / n, side = 0.5 * cell;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Vec3 lo{0.5 + (i + 0.25) * cell, 0.5 + (j + 0.25) * cell, 0.25};
      obj += ObjBox("cubes", "white", lo, lo + Vec3{side, side, side}, /*inward=*/false, next);
    }
  }
  return SceneFromObj(obj, kPlateMtl);
}

// Area-weighted mean of band 0 of `values` over the patches of scene object `object`.
inline double ObjectMean(const Scene& scene, const PatchMesh& mesh, const std::vector<Rgb>& values,
                         const std::string& object) {
  double sum = 0, area = 0;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    if (scene.objects[scene.faces[mesh.patches[p].face].object] != object) continue;
    sum += mesh.patches[p].area * values[p][0];
    area += mesh.patches[p].area;
  }
  return sum / area;
}

// In the two-plate scenes: F from the receiver "a" to the emitter "b", read back from the
// gathered radiosity (rho * E * F with rho 0.5, E = pi).
inline double GatheredFormFactor(const Scene& scene, const HierarchicalResult& r) {
  return ObjectMean(scene, r.mesh, r.solve.radiosity, "a") / (0.5 * std::numbers::pi);
}

// A hierarchical solve to tolerance 1e-9 (at most 500 sweeps) at the given link epsilon and
// samples per element.
inline HierarchicalResult SolvedHierarchical(const Scene& scene, double epsilon, int samples,
                                             bool clusters = true) {
  HierarchicalOptions options;
  options.enabled = true;
  options.link_epsilon = epsilon;
  options.samples = samples;
  options.clusters = clusters;
  SolverOptions solver;
  solver.tolerance = 1e-9;
  solver.max_iterations = 500;
  absl::StatusOr<HierarchicalResult> result = SolveHierarchical(scene, options, solver);
  EXPECT_TRUE(result.ok()) << result.status();
  return result.ok() ? *std::move(result) : HierarchicalResult{};
}

// Area-weighted RMS and mean over the leaves of B / exact - 1 (band 0).
inline std::pair<double, double> LeafRelativeError(const HierarchicalResult& r, double exact) {
  double sq = 0, area = 0, mean = 0;
  for (size_t i = 0; i < r.leaves.size(); ++i) {
    const double e = r.leaf_radiosity[i][0] / exact - 1, a = r.tree.nodes[r.leaves[i]].area;
    sq += a * e * e;
    mean += a * e;
    area += a;
  }
  return {std::sqrt(sq / area), mean / area};
}

}  // namespace radflux::testing
