// libFuzzer target: any bytes as a View3D .vs3 file (every record type: T, C, F, V, S, O, E,
// comments) must load to a model or a Status naming file:line, never crash, hang or trip a
// sanitizer; a model that loads must validate to OK or a Status.
#include <cstddef>
#include <cstdint>
#include <string>

#include "solver/scene/validation.h"
#include "solver/scene/vs3_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  absl::StatusOr<radflux::Vs3Model> model = radflux::LoadVs3Text(text, "fuzz.vs3");
  if (model.ok()) (void)radflux::ValidateScene(model->scene, /*require_emitter=*/false);
  return 0;
}
