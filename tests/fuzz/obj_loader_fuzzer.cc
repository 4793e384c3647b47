// libFuzzer target: any bytes as OBJ (and the second half as MTL) must load and validate
// to OK or a Status, never crash, hang or trip a sanitizer.
#include <cstddef>
#include <cstdint>
#include <string>

#include "solver/mesh/subdivide.h"
#include "solver/scene/obj_loader.h"
#include "solver/scene/validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t split = text.find("newmtl");
  const std::string obj = split == std::string::npos ? text : text.substr(0, split);
  const std::string mtl = split == std::string::npos ? "" : text.substr(split);
  absl::StatusOr<radflux::Scene> scene = radflux::LoadObjText(obj, mtl, "fuzz.obj");
  if (!scene.ok() || !radflux::ValidateScene(*scene).ok()) return 0;
  radflux::MeshOptions options;
  options.target_patches = 64;
  (void)radflux::SubdivideScene(*scene, options);
  return 0;
}
