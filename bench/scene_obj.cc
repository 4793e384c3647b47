// scene_obj SCENE OUT.obj: a scene as radflux loads it (any format LoadScene reads: MGF's
// colours, gamut and two-sided faces resolved), written as OBJ + MTL (OUT.mtl) for an outside
// renderer (issue 21: Cycles as a third judge of RenderPark's classroom).
//
// Faces are written once: a two-sided face's back-face twin is left out and its material is
// named with the suffix "_2s" (the renderer makes both sides alike: reflect Kd, emit Ke).
// Each object is an `o` group; Kd is the loaded (clamped) reflectance; Ke = E / pi, the
// emitted radiance, as the OBJ loader reads it back. Materials are named m<index>[_2s].
#include <cstdio>
#include <numbers>
#include <string>

#include "solver/scene/load_scene.h"

namespace radflux {
namespace {

int Run(const std::string& in, const std::string& out) {
  auto scene = LoadScene(in, ImportOptions{});
  if (!scene.ok()) return std::fprintf(stderr, "%s\n", scene.status().ToString().c_str()), 1;
  const std::string mtl = out.substr(0, out.rfind('.')) + ".mtl";
  FILE* m = std::fopen(mtl.c_str(), "w");
  FILE* o = std::fopen(out.c_str(), "w");
  if (!m || !o) return std::fprintf(stderr, "cannot write %s\n", out.c_str()), 1;
  auto name = [&](uint32_t k) {
    return "m" + std::to_string(k) + (scene->materials[k].two_sided ? "_2s" : "");
  };
  for (uint32_t k = 0; k < scene->materials.size(); ++k) {
    const Material& mat = scene->materials[k];
    std::fprintf(m, "newmtl %s\nKd %.9g %.9g %.9g\nKe %.9g %.9g %.9g\n", name(k).c_str(),
                 mat.reflectance[0], mat.reflectance[1], mat.reflectance[2],
                 mat.emission[0] / std::numbers::pi, mat.emission[1] / std::numbers::pi,
                 mat.emission[2] / std::numbers::pi);
  }
  const std::string base = mtl.substr(mtl.rfind('/') + 1);
  std::fprintf(o, "mtllib %s\n", base.c_str());
  for (const Vec3& v : scene->positions) std::fprintf(o, "v %.9g %.9g %.9g\n", v.x, v.y, v.z);
  uint32_t object = UINT32_MAX, material = UINT32_MAX;
  for (const Face& f : scene->faces) {
    if (f.back_face) continue;
    if (f.object != object) {
      object = f.object;
      std::fprintf(o, "o %s\n", scene->objects[object].c_str());
    }
    if (f.material != material) {
      material = f.material;
      std::fprintf(o, "usemtl %s\n", name(material).c_str());
    }
    std::fputc('f', o);
    for (uint32_t v : f.vertices) std::fprintf(o, " %u", v + 1);
    std::fputc('\n', o);
  }
  std::fclose(m);
  std::fclose(o);
  return 0;
}

}  // namespace
}  // namespace radflux

int main(int argc, char** argv) {
  if (argc != 3) return std::fprintf(stderr, "usage: scene_obj SCENE OUT.obj\n"), 2;
  return radflux::Run(argv[1], argv[2]);
}
