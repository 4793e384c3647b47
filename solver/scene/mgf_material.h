// The colour and material contexts of MGF (entities c, cxy, cspec, cct, cmix, m, rd, td, ed,
// rs, ts, sides) and their conversion to radflux materials.
//
// Conversion (see mgf_color.h for the colour space):
// - reflectance = linear RGB of (rd's colour, Y = rd);
// - emission E = linear RGB of (ed's colour, Y = ed / 179), W/m^2 per band: `ed` is a luminous
//   emittance in lm/m^2 and 179 lm/W is Radiance's efficacy of white light. (So an MGF
//   emitter of `ed 179` with the neutral colour emits E = 1 W/m^2 per band, L_e = 1/pi.)
// - two_sided = `sides 2` (the MGF default); `sides 1` is one-sided.
// - The specular reflection `rs`, specular transmission `ts` and diffuse transmission `td`
//   are read and checked but a diffuse solve has no place for them: each material that has
//   one is counted in the scene's import log (one line per kind), with the part's share of
//   all the light the material scatters, rs / (rd + rs + td + ts) for rs (the mean and the
//   largest over the materials are on the line and in the report).
// - A colour outside the RGB gamut (a negative band) is moved toward the neutral colour at
//   the same luminance until its lowest band is 0, so rd and ed keep their meaning; such
//   materials are counted too. (Bands above 1 are left to the import rules' clamp.)
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "solver/scene/mgf_color.h"
#include "solver/scene/scene.h"

namespace radflux {

// One MGF material's values as the file sets them.
struct MgfMaterialState {
  double rd = 0;                    // diffuse reflectance (photopic), [0, 1]
  double td = 0;                    // diffuse transmittance, [0, 1]
  double ed = 0;                    // diffuse emittance, lm/m^2
  double rs = 0, rs_roughness = 0;  // specular reflectance and its roughness
  double ts = 0, ts_roughness = 0;  // specular transmittance and its roughness
  MgfColor rd_color, td_color, ed_color, rs_color, ts_color;  // colour in force at each
  bool two_sided = true;                                      // sides 2 (MGF default) or 1

  bool operator==(const MgfMaterialState&) const = default;
};

// The radflux material for `state` named `name`; what it leaves out is counted in `log`
// with location `where`.
Material ConvertMgfMaterial(const std::string& name, const MgfMaterialState& state, ImportLog& log,
                            const std::string& where);

class MgfMaterialContext {
 public:
  MgfMaterialContext() = default;
  MgfMaterialContext(const MgfMaterialContext&) = delete;
  MgfMaterialContext& operator=(const MgfMaterialContext&) = delete;

  // Whether `entity` is one this context handles (listed above).
  static bool Handles(std::string_view entity);

  // Applies one statement of those entities. Error (no location) for a wrong number or type
  // of arguments, a value out of range or an undefined colour or material.
  absl::Status Apply(const std::vector<std::string>& words);

  // The index in scene.materials of the material in force, added (and converted) the first
  // time this name is used with these values; `where` ("file:line") is where it is used.
  uint32_t Intern(Scene& scene, const std::string& where);

 private:
  absl::Status ApplyColor(const std::vector<std::string>& words);
  absl::Status ApplyMaterial(const std::vector<std::string>& words);

  std::map<std::string, MgfColor> colors_;
  MgfColor unnamed_color_;
  MgfColor* color_ = &unnamed_color_;  // the colour in force (into colors_ or unnamed_color_)
  std::map<std::string, MgfMaterialState> materials_;
  MgfMaterialState unnamed_material_;
  MgfMaterialState* material_ = &unnamed_material_;
  std::string material_name_;  // empty for the unnamed material
  // Scene materials made so far: MGF name -> (values, index in scene.materials).
  std::map<std::string, std::vector<std::pair<MgfMaterialState, uint32_t>>> interned_;
};

}  // namespace radflux
