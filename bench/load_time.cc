// load_time FILE...: how long LoadScene takes on each scene file, any format it reads (the
// format's loader plus the import rules; no meshing: see load_mesh for OBJ by phase), as the
// median of 7 loads, with the face, material and file counts of the result.
//   build/release/bench/load_time ../shared/scenes/renderpark/salon/classroom.mgf
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "solver/scene/load_scene.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: load_time FILE...\n");
    return 2;
  }
  for (int a = 1; a < argc; ++a) {
    std::vector<double> ms;
    absl::StatusOr<radflux::Scene> scene;
    for (int run = 0; run < 7; ++run) {
      const auto start = std::chrono::steady_clock::now();
      scene = radflux::LoadScene(argv[a], radflux::ImportOptions{});
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count());
      if (!scene.ok()) break;
    }
    if (!scene.ok()) {
      std::fprintf(stderr, "%s\n", std::string(scene.status().message()).c_str());
      return 1;
    }
    std::sort(ms.begin(), ms.end());
    std::printf("%s: %zu faces, %zu materials, %zu files, %.2f ms (median of 7)\n", argv[a],
                scene->faces.size(), scene->materials.size(), scene->files.size(), ms[3]);
  }
  return 0;
}
