#include "solver/scene/gltf_material.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

constexpr char kEmissiveStrength[] = "KHR_materials_emissive_strength";

// The first three numbers of `factor` as an Rgb, if there are three and they are finite.
bool ReadRgb(const std::vector<double>& factor, Rgb& rgb) {
  if (factor.size() < 3) return false;
  for (int b = 0; b < kBands; ++b) {
    if (!std::isfinite(factor[b])) return false;
    rgb[b] = factor[b];
  }
  return true;
}

// KHR_materials_emissive_strength's emissiveStrength, 1 when absent.
double EmissiveStrength(const tinygltf::Material& material) {
  const auto it = material.extensions.find(kEmissiveStrength);
  if (it == material.extensions.end() || !it->second.IsObject()) return 1;
  const tinygltf::Value& strength = it->second.Get("emissiveStrength");
  return strength.IsNumber() ? strength.GetNumberAsDouble() : 1;
}

}  // namespace

absl::StatusOr<Material> ConvertMaterial(const tinygltf::Material& material, int index) {
  Material converted;
  converted.name = material.name.empty() ? absl::StrCat("material ", index) : material.name;
  const auto error = [&](const std::string& what) {
    return absl::InvalidArgumentError(absl::StrCat("material '", converted.name, "': ", what));
  };
  if (!ReadRgb(material.pbrMetallicRoughness.baseColorFactor, converted.reflectance)) {
    return error("baseColorFactor needs 3 finite numbers");
  }
  Rgb emissive{};
  if (!ReadRgb(material.emissiveFactor, emissive)) {
    return error("emissiveFactor needs 3 finite numbers");
  }
  const double strength = EmissiveStrength(material);
  if (!std::isfinite(strength) || strength < 0) {
    return error(absl::StrCat(kEmissiveStrength, " emissiveStrength must be finite and >= 0"));
  }
  for (int b = 0; b < kBands; ++b) {
    converted.emission[b] = std::numbers::pi * (emissive[b] * strength);
  }
  converted.two_sided = material.doubleSided;
  return converted;
}

Material DefaultMaterial() {
  Material material;
  material.name = "default";
  material.reflectance = {1, 1, 1};
  return material;
}

void NoteMaterialLosses(const tinygltf::Material& material, const std::string& where,
                        ImportLog& log) {
  if (material.pbrMetallicRoughness.metallicFactor > 0) {
    log.Add("gltf_metallic_as_diffuse",
            "glTF {material|materials} with metallicFactor > 0 read as diffuse (base colour as reflectance)",
            where);
  }
}

}  // namespace radflux
