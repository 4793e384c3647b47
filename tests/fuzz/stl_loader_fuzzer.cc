// libFuzzer target: any bytes as STL, binary or ASCII (after a line "@@", the groups side
// file), must load to a Scene or a Status, never crash, hang or trip a sanitizer; a scene
// that validates and has few faces then gets its view-factor rows (the per-pair integrator
// on whatever geometry the loader lets through), each in [0, 1].
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "solver/formfactor/surface_rows.h"
#include "solver/scene/stl_loader.h"
#include "solver/scene/validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const size_t split = bytes.find("\n@@\n");
  std::optional<std::string> groups;
  if (split != std::string::npos) groups = bytes.substr(split + 4);
  absl::StatusOr<radflux::Scene> scene =
      radflux::LoadStlBytes(bytes.substr(0, split), "fuzz.stl", groups);
  if (!scene.ok() || scene->faces.size() > 12 ||
      !radflux::ValidateScene(*scene, /*require_emitter=*/false).ok()) {
    return 0;
  }
  std::vector<radflux::SurfaceShape> shapes;
  for (const radflux::Face& face : scene->faces) {
    shapes.push_back(radflux::MakeSurfaceShape(radflux::FacePolygon(*scene, face)));
  }
  radflux::SurfaceRowsOptions options;
  options.threads = 1;
  radflux::SurfaceRowsStats stats;
  (void)radflux::BuildSurfaceRows(
      shapes, shapes.size(), options,
      [](std::span<const double> row) {
        for (double f : row) {
          if (!(f >= 0 && f <= 1)) std::abort();
        }
        return absl::OkStatus();
      },
      stats);
  return 0;
}
