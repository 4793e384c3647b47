// load_mesh FILE [PATCHES] [RUNS]: the time to read a scene as `radflux solve` does, by
// phase, as the median of RUNS (default 5) runs: parse (the OBJ loader), import rules,
// and mesh (subdivision to PATCHES patches, default 2000 as the CLI, and patch attributes).
// Issue 19's target: load + mesh of the conference room (330,837 faces) <= 1.5 s.
//   build/release/bench/load_mesh ../shared/scenes/conference/conference.obj
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/subdivide.h"
#include "solver/scene/import_rules.h"
#include "solver/scene/obj_loader.h"

namespace {

double Since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: load_mesh FILE.obj [PATCHES] [RUNS]\n");
    return 2;
  }
  const int64_t patches = argc > 2 ? std::atoll(argv[2]) : 2000;
  const int runs = argc > 3 ? std::atoi(argv[3]) : 5;
  std::vector<double> parse, rules, mesh, total;
  size_t faces = 0, patch_count = 0;
  for (int run = 0; run < runs; ++run) {
    auto start = std::chrono::steady_clock::now();
    absl::StatusOr<radflux::Scene> scene = radflux::LoadObjFile(argv[1]);
    if (!scene.ok()) {
      std::fprintf(stderr, "%s\n", std::string(scene.status().message()).c_str());
      return 1;
    }
    parse.push_back(Since(start));
    start = std::chrono::steady_clock::now();
    radflux::ImportOptions options;
    options.emit = {{scene->materials.at(0).name, radflux::Rgb{1, 1, 1}}};  // any light
    if (absl::Status s = radflux::ApplyImportRules(options, *scene); !s.ok()) {
      std::fprintf(stderr, "%s\n", std::string(s.message()).c_str());
      return 1;
    }
    rules.push_back(Since(start));
    start = std::chrono::steady_clock::now();
    radflux::MeshOptions mesh_options;
    mesh_options.target_patches = patches;
    absl::StatusOr<radflux::PatchMesh> patch_mesh = radflux::SubdivideScene(*scene, mesh_options);
    if (!patch_mesh.ok()) return 1;
    const radflux::PatchAttributes attributes = radflux::ComputePatchAttributes(*scene, *patch_mesh);
    mesh.push_back(Since(start));
    total.push_back(parse.back() + rules.back() + mesh.back());
    faces = scene->faces.size();
    patch_count = attributes.area.size();
  }
  std::printf("%s: %zu faces -> %zu patches; median of %d runs: parse %.3f s, rules %.3f s, "
              "mesh %.3f s, load + mesh %.3f s\n",
              argv[1], faces, patch_count, runs, Median(parse), Median(rules), Median(mesh),
              Median(total));
  return 0;
}
