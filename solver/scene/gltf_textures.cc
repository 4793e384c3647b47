#include "solver/scene/gltf_textures.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "solver/scene/gltf_accessor.h"

namespace radflux {
namespace {

constexpr char kTextureTransform[] = "KHR_texture_transform";

// The reader's key of image `i`: its URI when it is an external file, else "image <i>".
std::string ImageKey(const tinygltf::Model& model, int i) {
  const std::string& uri = model.images[i].uri;
  return uri.empty() ? absl::StrCat("image ", i) : uri;
}

// Number `k` of the array `value` (a JSON value of tinygltf), or `otherwise`.
double Element(const tinygltf::Value& value, int k, double otherwise) {
  if (!value.IsArray() || static_cast<int>(value.ArrayLen()) <= k) return otherwise;
  const tinygltf::Value& v = value.Get(k);
  return v.IsNumber() ? v.GetNumberAsDouble() : otherwise;
}

// The coordinate set of `info`: its texCoord, or KHR_texture_transform's offset, rotation,
// scale and texCoord as the extension composes them (T * R * S).
absl::StatusOr<GltfTexCoordSet> CoordinateSet(const tinygltf::TextureInfo& info) {
  GltfTexCoordSet set{info.texCoord, {1, 0, 0, 0, 1, 0}};
  const auto it = info.extensions.find(kTextureTransform);
  if (it == info.extensions.end() || !it->second.IsObject()) return set;
  const tinygltf::Value& x = it->second;
  const double r = x.Get("rotation").IsNumber() ? x.Get("rotation").GetNumberAsDouble() : 0;
  const double sx = Element(x.Get("scale"), 0, 1), sy = Element(x.Get("scale"), 1, 1);
  const double c = std::cos(r), s = std::sin(r);
  set.transform = {c * sx, s * sy, Element(x.Get("offset"), 0, 0),
                   -s * sx, c * sy, Element(x.Get("offset"), 1, 0)};
  for (double t : set.transform) {
    if (!std::isfinite(t)) {
      return absl::InvalidArgumentError(absl::StrCat(kTextureTransform, " is not finite"));
    }
  }
  if (x.Get("texCoord").IsInt()) set.set = x.Get("texCoord").GetNumberAsInt();
  return set;
}

// The reader key of texture `index` ("" for none): its image's key, or "texture <index>"
// when it has no image in a core format (the reader then says so).
absl::StatusOr<std::string> TextureKey(const tinygltf::Model& model, int index) {
  if (index < 0) return std::string();
  if (static_cast<size_t>(index) >= model.textures.size()) {
    return absl::InvalidArgumentError(absl::StrCat("texture ", index, " does not exist"));
  }
  const int source = model.textures[index].source;
  if (source < 0 || static_cast<size_t>(source) >= model.images.size()) {
    return absl::StrCat("texture ", index);
  }
  return ImageKey(model, source);
}

// One of a sampler's wrapS / wrapT (glTF's GL enums; REPEAT, the default, for any other).
TextureWrap WrapOf(int mode) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return TextureWrap::kClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return TextureWrap::kMirroredRepeat;
    default:
      return TextureWrap::kRepeat;
  }
}

// The wrap modes of texture `index`'s sampler: repeat on both axes when it has none (or
// names one that does not exist, or there is no texture).
TextureWrapping WrappingOf(const tinygltf::Model& model, int index) {
  if (index < 0 || static_cast<size_t>(index) >= model.textures.size()) return {};
  const int sampler = model.textures[index].sampler;
  if (sampler < 0 || static_cast<size_t>(sampler) >= model.samplers.size()) return {};
  return {WrapOf(model.samplers[sampler].wrapS), WrapOf(model.samplers[sampler].wrapT)};
}

}  // namespace

absl::StatusOr<GltfMaterialTextures> ReadGltfMaterialTextures(const tinygltf::Model& model,
                                                              int index) {
  const tinygltf::Material& material = model.materials[index];
  const auto error = [&](absl::string_view what) {
    return absl::InvalidArgumentError(absl::StrCat(
        "material '", material.name.empty() ? absl::StrCat("material ", index) : material.name,
        "': ", what));
  };
  const tinygltf::TextureInfo& base = material.pbrMetallicRoughness.baseColorTexture;
  absl::StatusOr<std::string> diffuse = TextureKey(model, base.index);
  absl::StatusOr<std::string> emissive = TextureKey(model, material.emissiveTexture.index);
  absl::StatusOr<GltfTexCoordSet> base_set = CoordinateSet(base);
  absl::StatusOr<GltfTexCoordSet> emissive_set = CoordinateSet(material.emissiveTexture);
  for (const absl::Status& s :
       {diffuse.status(), emissive.status(), base_set.status(), emissive_set.status()}) {
    if (!s.ok()) return error(s.message());
  }
  GltfMaterialTextures out{{*diffuse, *emissive, ""}, *base_set, *emissive_set};
  out.textures.diffuse_wrap = WrappingOf(model, base.index);
  out.textures.emissive_wrap = WrappingOf(model, material.emissiveTexture.index);
  const std::vector<double>& factor = material.pbrMetallicRoughness.baseColorFactor;
  if (material.alphaMode == "MASK" || material.alphaMode == "BLEND") {
    out.textures.alpha = *diffuse;
    out.textures.alpha_wrap = out.textures.diffuse_wrap;
    out.textures.alpha_scale = factor.size() > 3 && std::isfinite(factor[3]) ? factor[3] : 1;
    if (material.alphaMode == "MASK") out.textures.alpha_cutoff = material.alphaCutoff;
  }
  return out;
}

TextureReader GltfImageReader(const tinygltf::Model& model, const TextureReader& fallback) {
  return [&model, fallback](const std::string& key) -> absl::StatusOr<std::string> {
    for (size_t i = 0; i < model.images.size(); ++i) {
      if (ImageKey(model, static_cast<int>(i)) != key) continue;
      const tinygltf::Image& image = model.images[i];
      if (!image.image.empty()) return std::string(image.image.begin(), image.image.end());
      if (image.bufferView >= 0) {
        absl::StatusOr<absl::string_view> bytes = BufferViewBytes(model, image.bufferView);
        if (!bytes.ok()) return absl::NotFoundError(bytes.status().message());
        return std::string(*bytes);
      }
      if (!image.uri.empty() && fallback) return fallback(image.uri);
      return absl::NotFoundError("no such file");
    }
    return absl::NotFoundError("no image in a format radflux reads");
  };
}

std::vector<TexCoord> TransformTexCoords(const GltfTexCoordSet& set, std::vector<TexCoord> uv) {
  const std::array<double, 6>& t = set.transform;
  if (t == GltfTexCoordSet{}.transform) return uv;
  for (TexCoord& c : uv) c = {t[0] * c[0] + t[1] * c[1] + t[2], t[3] * c[0] + t[4] * c[1] + t[5]};
  return uv;
}

}  // namespace radflux
