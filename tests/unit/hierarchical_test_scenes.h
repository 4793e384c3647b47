// Scenes and helpers shared by the hierarchical and adaptive tests: two-plate scenes where
// one plate emits (rho 0) and the other reflects, so the receiver's mean B is rho * E * F.
#pragma once

#include <string>
#include <vector>

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

// Area-weighted mean of band 0 of `values` over the patches of scene object `object`.
inline double ObjectMean(const Scene& scene, const PatchMesh& mesh,
                         const std::vector<Rgb>& values, const std::string& object) {
  double sum = 0, area = 0;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    if (scene.objects[scene.faces[mesh.patches[p].face].object] != object) continue;
    sum += mesh.patches[p].area * values[p][0];
    area += mesh.patches[p].area;
  }
  return sum / area;
}

}  // namespace radflux::testing
