#include "solver/scene/mgf_material.h"

#include <algorithm>
#include <array>

#include "absl/strings/str_cat.h"
#include "solver/scene/mgf_tokenizer.h"

namespace radflux {
namespace {

absl::Status Error(const std::string& entity, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat("'", entity, "' ", what));
}

// The numbers words[1..], which must be exactly `count` of them.
absl::Status Numbers(const std::vector<std::string>& words, size_t count, double* out) {
  if (words.size() != count + 1) {
    return Error(words[0], absl::StrCat("needs ", count, " number", count > 1 ? "s" : ""));
  }
  for (size_t i = 0; i < count; ++i) {
    if (!ParseMgfNumber(words[i + 1], &out[i])) {
      return Error(words[0], absl::StrCat("argument '", words[i + 1], "' is not a number"));
    }
  }
  return absl::OkStatus();
}

// `rgb` (of luminance y) moved toward the neutral (y, y, y) along the line of constant
// luminance just far enough that no band is negative; true when it had to move.
bool DesaturateIntoGamut(Rgb& rgb, double y) {
  double t = 1;  // share of the original colour kept
  for (double v : rgb) {
    if (v < 0) t = std::min(t, y / (y - v));
  }
  if (t == 1) return false;
  for (double& v : rgb) v = std::max(0.0, y + t * (v - y));
  return true;
}

// The named entry of `table` chosen, defined or copied by a `c`/`m` statement:
// "name" (must exist), "name =" (reset to `fresh`), "name = template".
template <typename T>
absl::StatusOr<T*> SelectNamed(std::map<std::string, T>& table,
                               const std::vector<std::string>& words, const T& fresh) {
  const std::string& entity = words[0];
  if (words.size() > 4) return Error(entity, "has too many arguments");
  if (words.size() == 2) {
    auto it = table.find(words[1]);
    if (it == table.end()) return Error(entity, absl::StrCat("'", words[1], "' is not defined"));
    return &it->second;
  }
  if (words[2] != "=") return Error(entity, "expects '=' after the name");
  T value = fresh;
  if (words.size() == 4) {
    auto it = table.find(words[3]);
    if (it == table.end())
      return Error(entity, absl::StrCat("template '", words[3], "' is not defined"));
    value = it->second;
  }
  T& slot = table[words[1]];
  slot = value;
  return &slot;
}

}  // namespace

Material ConvertMgfMaterial(const std::string& name, const MgfMaterialState& state, ImportLog& log,
                            const std::string& where) {
  Material m;
  m.name = name;
  m.two_sided = state.two_sided;
  const double emitted_y = state.ed / kMgfLumensPerWatt;
  m.reflectance = XyYToLinearRgb(state.rd_color, state.rd);
  m.emission = XyYToLinearRgb(state.ed_color, emitted_y);
  const bool moved_r = DesaturateIntoGamut(m.reflectance, state.rd);
  const bool moved_e = DesaturateIntoGamut(m.emission, emitted_y);
  if (moved_r || moved_e) {
    log.Add("mgf_colour_out_of_gamut",
            "MGF {material|materials} with a colour outside the RGB gamut, desaturated at the same "
            "luminance",
            where);
  }
  // Each part left out, as a share of all the light the material scatters.
  const double scattered = state.rd + state.rs + state.td + state.ts;
  const std::string share_of = "of the light {it scatters|they scatter} (rd + rs + td + ts)";
  if (state.rs > 0) {
    log.AddShare("mgf_specular_reflection_left_out",
                 "MGF {material|materials} with a specular reflection part (rs) left out of the "
                 "diffuse solve",
                 where, state.rs / scattered, share_of);
  }
  if (state.ts > 0) {
    log.AddShare("mgf_specular_transmission_left_out",
                 "MGF {material|materials} with a specular transmission part (ts) left out of the "
                 "diffuse solve",
                 where, state.ts / scattered, share_of);
  }
  if (state.td > 0) {
    log.AddShare("mgf_diffuse_transmission_left_out",
                 "MGF {material|materials} with a diffuse transmission part (td) left out of the "
                 "diffuse solve",
                 where, state.td / scattered, share_of);
  }
  return m;
}

bool MgfMaterialContext::Handles(std::string_view entity) {
  static constexpr std::array<std::string_view, 12> kEntities = {
      "c", "cxy", "cspec", "cct", "cmix", "m", "rd", "td", "ed", "rs", "ts", "sides"};
  return std::find(kEntities.begin(), kEntities.end(), entity) != kEntities.end();
}

absl::Status MgfMaterialContext::Apply(const std::vector<std::string>& words) {
  if (words[0][0] == 'c') return ApplyColor(words);
  return ApplyMaterial(words);
}

absl::Status MgfMaterialContext::ApplyColor(const std::vector<std::string>& words) {
  const std::string& e = words[0];
  if (e == "c") {
    if (words.size() == 1) {
      unnamed_color_ = MgfColor{};
      color_ = &unnamed_color_;
      return absl::OkStatus();
    }
    absl::StatusOr<MgfColor*> selected = SelectNamed(colors_, words, MgfColor{});
    if (!selected.ok()) return selected.status();
    color_ = *selected;
    return absl::OkStatus();
  }
  if (e == "cxy") {
    double xy[2];
    if (absl::Status s = Numbers(words, 2, xy); !s.ok()) return s;
    if (xy[0] < 0 || xy[1] <= 0 || xy[0] + xy[1] > 1) {
      return Error(e, "chromaticity must satisfy x >= 0, y > 0, x + y <= 1");
    }
    *color_ = {xy[0], xy[1]};
    return absl::OkStatus();
  }
  std::vector<double> values;
  for (size_t i = 1; i < words.size(); ++i) {
    double v = 0;
    if (!ParseMgfNumber(words[i], &v) && !(e == "cmix" && i % 2 == 0)) {
      return Error(e, absl::StrCat("argument '", words[i], "' is not a number"));
    }
    values.push_back(v);
  }
  absl::StatusOr<MgfColor> color;
  if (e == "cspec") {
    if (values.size() < 4) return Error(e, "needs wl_min wl_max and at least two samples");
    color = SpectrumChromaticity(values[0], values[1],
                                 std::vector<double>(values.begin() + 2, values.end()));
  } else if (e == "cct") {
    if (values.size() != 1) return Error(e, "needs 1 number");
    color = BlackbodyChromaticity(values[0]);
  } else {  // cmix w1 c1 w2 c2 ...
    if (values.size() < 4 || values.size() % 2 != 0) return Error(e, "needs weight-colour pairs");
    std::vector<double> weights;
    std::vector<MgfColor> mixed;
    for (size_t i = 1; i < words.size(); i += 2) {
      auto it = colors_.find(words[i + 1]);
      if (it == colors_.end()) return Error(e, absl::StrCat("'", words[i + 1], "' is not defined"));
      if (values[i - 1] < 0) return Error(e, "weights must be >= 0");
      weights.push_back(values[i - 1]);
      mixed.push_back(it->second);
    }
    double sum = 0;
    for (double w : weights) sum += w;
    if (!(sum > 0)) return Error(e, "weights must have a positive sum");
    color = MixColors(weights, mixed);
  }
  if (!color.ok()) return color.status();
  *color_ = *color;
  return absl::OkStatus();
}

absl::Status MgfMaterialContext::ApplyMaterial(const std::vector<std::string>& words) {
  const std::string& e = words[0];
  if (e == "m") {
    if (words.size() == 1) {
      unnamed_material_ = MgfMaterialState{};
      material_ = &unnamed_material_;
      material_name_.clear();
      return absl::OkStatus();
    }
    absl::StatusOr<MgfMaterialState*> selected = SelectNamed(materials_, words, MgfMaterialState{});
    if (!selected.ok()) return selected.status();
    material_ = *selected;
    material_name_ = words[1];
    return absl::OkStatus();
  }
  MgfMaterialState& m = *material_;
  double v[2] = {0, 0};
  const size_t count = (e == "rs" || e == "ts") ? 2 : 1;
  if (absl::Status s = Numbers(words, count, v); !s.ok()) return s;
  if (e == "sides") {
    if (v[0] != 1 && v[0] != 2) return Error(e, "must be 1 or 2");
    m.two_sided = v[0] == 2;
    return absl::OkStatus();
  }
  if (v[0] < 0 || (e != "ed" && v[0] > 1) || v[1] < 0) {
    return Error(e, e == "ed" ? "must be >= 0" : "must be in [0, 1] (roughness >= 0)");
  }
  if (e == "rd") m.rd = v[0], m.rd_color = *color_;
  if (e == "td") m.td = v[0], m.td_color = *color_;
  if (e == "ed") m.ed = v[0], m.ed_color = *color_;
  if (e == "rs") m.rs = v[0], m.rs_roughness = v[1], m.rs_color = *color_;
  if (e == "ts") m.ts = v[0], m.ts_roughness = v[1], m.ts_color = *color_;
  return absl::OkStatus();
}

uint32_t MgfMaterialContext::Intern(Scene& scene, const std::string& where) {
  std::vector<std::pair<MgfMaterialState, uint32_t>>& versions = interned_[material_name_];
  for (const auto& [state, index] : versions) {
    if (state == *material_) return index;
  }
  std::string name = material_name_.empty() ? "(unnamed)" : material_name_;
  if (!versions.empty()) name = absl::StrCat(name, "#", versions.size() + 1);
  const uint32_t index = static_cast<uint32_t>(scene.materials.size());
  scene.materials.push_back(ConvertMgfMaterial(name, *material_, scene.import_log, where));
  versions.push_back({*material_, index});
  return index;
}

}  // namespace radflux
