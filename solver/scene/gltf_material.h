// glTF 2.0 materials as radflux's diffuse materials: baseColorFactor (linear RGB) is the
// reflectance, emissiveFactor times KHR_materials_emissive_strength the emitted radiance L_e
// (so Material::emission = pi * L_e), doubleSided makes faces two-sided; textures multiply
// these per face (gltf_textures.h). Reflectance at or above 1 is left for the shared import
// rules to clamp.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/import_log.h"
#include "solver/scene/scene.h"
#include "tiny_gltf.h"

namespace radflux {

// Material `index` of a model; its name is the glTF name, or "material <index>" when it has
// none. INVALID_ARGUMENT (message naming the material) when a factor has fewer than three
// numbers or a value that is not finite.
absl::StatusOr<Material> ConvertMaterial(const tinygltf::Material& material, int index);

// glTF's default material, for primitives that name none: base colour (1, 1, 1), no
// emission, single-sided; named "default". (glTF makes it metallic; a file that names no
// material means no metal, so this is not noted as a loss.)
Material DefaultMaterial();

// Records in `log` what a diffuse solve leaves out of `material` (used at `where`): its
// metallic part (metallicFactor > 0 is read as diffuse). Its textures are read:
// gltf_textures.h.
void NoteMaterialLosses(const tinygltf::Material& material, const std::string& where,
                        ImportLog& log);

}  // namespace radflux
