#include "solver/scene/emitters.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace radflux {

absl::Status ApplyEmitOptions(const std::vector<std::pair<std::string, Rgb>>& emit, Scene& scene) {
  for (const auto& entry : emit) {
    const std::string& name = entry.first;
    const Rgb& radiance = entry.second;
    bool found = false;  // every material of that name (textures make copies of one)
    for (Material& m : scene.materials) {
      if (m.name != name) continue;
      found = true;
      for (int b = 0; b < kBands; ++b) {
        if (!std::isfinite(radiance[b]) || radiance[b] < 0) {
          return absl::InvalidArgumentError(
              absl::StrCat("--emit ", name, ": emitted radiance must be finite and >= 0"));
        }
        m.emission[b] = std::numbers::pi * radiance[b];
      }
    }
    if (!found) {
      return absl::InvalidArgumentError(
          absl::StrCat("--emit ", name, "=...: ", scene.source, " has no material '", name, "'"));
    }
  }
  return absl::OkStatus();
}

std::string NoEmitterMessage(const Scene& scene) {
  std::vector<double> area(scene.materials.size(), 0.0);
  for (const Face& face : scene.faces) {
    area[face.material] += Length(PolygonNewellNormal(FacePolygon(scene, face))) / 2;
  }
  std::vector<size_t> order;
  for (size_t m = 0; m < area.size(); ++m) {
    if (area[m] > 0) order.push_back(m);
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return area[a] > area[b]; });
  std::string largest;
  for (size_t k = 0; k < std::min<size_t>(5, order.size()); ++k) {
    absl::StrAppend(&largest, k == 0 ? "" : ", ",
                    absl::StrFormat("'%s' (%.4g)", scene.materials[order[k]].name, area[order[k]]));
  }
  return absl::StrCat(scene.source,
                      ": no emitter (no face's material has Ke > 0); light it with --emit "
                      "MATERIAL=R,G,B (emitted radiance L_e, repeatable); the materials with the "
                      "largest area: ",
                      largest);
}

}  // namespace radflux
