// libFuzzer target: any bytes as an MGF file must load (and validate) to OK or a Status,
// never crash, hang or trip a sanitizer. Text after a line "@@" is the file "inc.mgf" that
// `i inc.mgf` (from any folder) includes, so includes, their transforms and cycles are
// reached too. Small limits keep each input fast; the limits' own checks are what stop
// huge arrays.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "solver/mesh/subdivide.h"
#include "solver/scene/mgf_loader.h"
#include "solver/scene/validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t split = text.find("\n@@\n");
  const std::string main_text = split == std::string::npos ? text : text.substr(0, split);
  const std::string include = split == std::string::npos ? "" : text.substr(split + 4);
  const radflux::MgfFileReader reader =
      [&](const std::string& path) -> absl::StatusOr<std::string> {
    if (std::filesystem::path(path).filename() == "inc.mgf") return include;
    return absl::NotFoundError("no such file");
  };
  radflux::ImportOptions options;
  options.curve_segments = 6;
  radflux::MgfLimits limits;
  limits.max_statements = 100000;
  limits.max_faces = 5000;
  absl::StatusOr<radflux::Scene> scene =
      radflux::LoadMgfText(main_text, "fuzz.mgf", options, reader, limits);
  if (!scene.ok() || !radflux::ValidateScene(*scene).ok()) return 0;
  radflux::MeshOptions mesh_options;
  mesh_options.target_patches = 64;
  (void)radflux::SubdivideScene(*scene, mesh_options);
  return 0;
}
