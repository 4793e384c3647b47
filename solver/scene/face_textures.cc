#include "solver/scene/face_textures.h"

#include <map>
#include <optional>
#include <tuple>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

// Each texture decoded once; a texture that cannot be read is logged once and is null.
// Opacity images (alpha replaced by a material's opacity rule) are derived once per rule.
class TextureCache {
 public:
  TextureCache(const TextureReader& read, const TextureFormat& format, ImportLog& log)
      : read_(read), format_(format), log_(log) {}

  const TextureImage* Get(const std::string& name) {
    if (name.empty()) return nullptr;
    auto [it, inserted] = images_.try_emplace(name);
    if (!inserted) return it->second ? &*it->second : nullptr;
    absl::StatusOr<std::string> bytes = read_(name);
    absl::StatusOr<TextureImage> image =
        bytes.ok() ? DecodeTexture(*bytes, name)
                   : absl::StatusOr<TextureImage>(
                         absl::NotFoundError(absl::StrCat(name, ": ", bytes.status().message())));
    if (!image.ok()) {
      log_.Add(
          "textures_not_read",
          absl::StrCat("{texture|textures} not read; the materials using {it|them} keep their ",
                       format_.untextured),
          std::string(image.status().message()));
      return nullptr;
    }
    it->second = *std::move(image);
    return &*it->second;
  }

  // The alpha texture of `textures` with each texel's alpha its opacity
  // (MaterialTextures' rule), or null when there is none.
  const TextureImage* Opacity(const MaterialTextures& textures) {
    const TextureImage* image = Get(textures.alpha);
    if (image == nullptr) return nullptr;
    const bool grey = format_.alpha_from_grey && !image->has_alpha;
    if (!grey && textures.alpha_scale == 1 && textures.alpha_cutoff < 0) return image;
    auto [it, inserted] = opacity_.try_emplace(
        std::make_tuple(textures.alpha, textures.alpha_scale, textures.alpha_cutoff));
    if (inserted) {
      it->second = *image;
      for (std::array<float, 4>& t : it->second.texels) {
        // A grey image's texels hold its decoded (linear) grey: the byte is the opacity.
        const double alpha = (grey ? LinearToSrgb(t[0]) : t[3]) * textures.alpha_scale;
        t[3] =
            static_cast<float>(textures.alpha_cutoff < 0 ? alpha : alpha >= textures.alpha_cutoff);
      }
    }
    return &it->second;
  }

 private:
  const TextureReader& read_;
  const TextureFormat& format_;
  ImportLog& log_;
  std::map<std::string, std::optional<TextureImage>> images_;
  std::map<std::tuple<std::string, double, double>, TextureImage> opacity_;
};

Rgb Times(const Rgb& a, const std::array<double, 4>& mean) {
  return {a[0] * mean[0], a[1] * mean[1], a[2] * mean[2]};
}

// The mean opacity of face f over its alpha texture's footprint (1 without one), or nullopt
// when it is cut out (below kMinOpacity); logs what it decides.
std::optional<double> FaceOpacity(const MaterialTextures& textures, const std::vector<TexCoord>& uv,
                                  const TextureFormat& format, const std::string& where,
                                  TextureCache& cache, ImportLog& log) {
  const TextureImage* opacity = cache.Opacity(textures);
  if (opacity == nullptr || uv.empty()) return 1.0;
  const double alpha = TextureMean(*opacity, uv, format.v_up, textures.alpha_wrap)[3];
  if (alpha < kMinOpacity) {
    log.Add("transparent_faces_dropped",
            absl::StrCat("{face|faces} transparent (mean alpha < 1/255) in {its|their} alpha "
                         "texture (",
                         format.alpha, ") dropped"),
            where);
    return std::nullopt;
  }
  if (alpha < 1) {
    log.Add("partly_transparent",
            absl::StrCat("{face|faces} partly transparent (mean alpha in [1/255, 1)) in "
                         "{its|their} alpha texture (",
                         format.alpha, ") let the transparent fraction through"),
            where);
  }
  return alpha;
}

}  // namespace

void ApplyFaceTextures(const std::vector<MaterialTextures>& textures, const FaceTexCoords& uvs,
                       const TextureReader& read, const TextureFormat& format, Scene& scene) {
  TextureCache cache(read, format, scene.import_log);
  // (material, rho, E, opacity) -> index
  std::map<std::tuple<uint32_t, Rgb, Rgb, double>, uint32_t> variants;
  std::vector<Face> kept;
  kept.reserve(scene.faces.size());
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    Face& face = scene.faces[f];
    const MaterialTextures& slots = textures[face.material];
    const std::string where = face.source_line > 0 ? scene.FaceLocation(f) : scene.DescribeFace(f);
    if (!slots.any()) {
      kept.push_back(std::move(face));
      continue;
    }
    const std::optional<double> opacity =
        FaceOpacity(slots, uvs(f, TextureSlot::kAlpha), format, where, cache, scene.import_log);
    if (!opacity) continue;
    Material material = scene.materials[face.material];
    material.opacity = *opacity;
    bool without_uv = false;
    const auto apply = [&](const std::string& name, TextureWrapping wrap, TextureSlot slot,
                           Rgb& value, const char* kind, const std::string& message) {
      const TextureImage* image = cache.Get(name);
      if (image == nullptr) return;
      const std::vector<TexCoord>& uv = uvs(f, slot);
      if (uv.empty()) {
        without_uv = true;
        return;
      }
      value = Times(value, TextureMean(*image, uv, format.v_up, wrap));
      scene.import_log.Add(kind, message, where);
    };
    apply(slots.diffuse, slots.diffuse_wrap, TextureSlot::kDiffuse, material.reflectance,
          "reflectance_from_textures",
          absl::StrCat("{face|faces} took {its|their} reflectance from textures (", format.diffuse,
                       ")"));
    apply(slots.emissive, slots.emissive_wrap, TextureSlot::kEmissive, material.emission,
          "emission_from_textures",
          absl::StrCat("{face|faces} took {its|their} emission from textures (", format.emissive,
                       ")"));
    if (without_uv || (!slots.alpha.empty() && uvs(f, TextureSlot::kAlpha).empty())) {
      scene.import_log.Add("textures_without_uv",
                           absl::StrCat("{face|faces} in textured materials without texture "
                                        "coordinates kept {its|their} ",
                                        format.untextured),
                           where);
    }
    const auto key =
        std::make_tuple(face.material, material.reflectance, material.emission, material.opacity);
    auto [it, inserted] = variants.try_emplace(key, static_cast<uint32_t>(scene.materials.size()));
    if (inserted) scene.materials.push_back(std::move(material));
    face.material = it->second;
    kept.push_back(std::move(face));
  }
  scene.faces = std::move(kept);
}

}  // namespace radflux
