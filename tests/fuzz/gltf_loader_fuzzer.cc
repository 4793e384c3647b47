// libFuzzer target: any bytes as a .gltf or .glb (from memory, so no file is read) must load
// and validate to OK or a Status, never crash, hang or trip a sanitizer.
#include <cstddef>
#include <cstdint>
#include <string>

#include "solver/mesh/subdivide.h"
#include "solver/scene/gltf_loader.h"
#include "solver/scene/validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  absl::StatusOr<radflux::Scene> scene = radflux::LoadGltfData(bytes, "fuzz.gltf", {});
  // Meshing is the OBJ fuzzer's subject; here it only checks that a loaded scene meshes, on
  // scenes small enough to keep each run short.
  if (!scene.ok() || scene->faces.size() > 4096 || !radflux::ValidateScene(*scene).ok()) return 0;
  radflux::MeshOptions options;
  options.target_patches = 64;
  (void)radflux::SubdivideScene(*scene, options);
  return 0;
}
