#include "solver/scene/gltf_loader.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "solver/scene/file_lookup.h"
#include "solver/scene/gltf_accessor.h"
#include "solver/scene/gltf_material.h"
#include "solver/scene/gltf_nodes.h"
#include "solver/scene/gltf_parse.h"
#include "solver/scene/gltf_primitive.h"
#include "solver/scene/gltf_textures.h"

namespace radflux {
namespace {

// Texture coordinates of one face: the base colour texture's (the alpha's too) and the
// emissive texture's.
using FaceUv = std::array<std::vector<TexCoord>, 2>;

// The texture coordinate sets one primitive's material reads (u, v per vertex), by set.
struct PrimitiveUv {
  const GltfMaterialTextures* textures = nullptr;
  std::map<int, std::vector<double>> sets;

  // The coordinates of triangle `t` (the primitive's vertex indices), each set transformed
  // as its texture says; empty for a set the primitive does not have.
  FaceUv Of(const Triangle& t) const {
    FaceUv out;
    const GltfTexCoordSet* slots[2] = {&textures->base, &textures->emissive};
    for (int k = 0; k < 2; ++k) {
      const auto it = sets.find(slots[k]->set);
      if (it == sets.end()) continue;
      std::vector<TexCoord> uv;
      for (const uint32_t i : t) uv.push_back({it->second[2 * i], it->second[2 * i + 1]});
      out[k] = TransformTexCoords(*slots[k], std::move(uv));
    }
    return out;
  }
};

// The scene being built from one model, and how glTF's materials, nodes and meshes map
// onto its materials, objects and groups.
class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, const std::string& name, const ImportOptions& options)
      : model_(model), name_(name), options_(options), noted_(model.materials.size(), false) {
    scene_.source = name;
    scene_.files = {name};
  }

  absl::Status AddMaterials();
  absl::Status AddInstance(const MeshInstance& instance);
  // The scene, its textures applied (images read by `fallback` when not in the model).
  Scene Take(const TextureReader& fallback);

 private:
  // `positions`: the first scene vertex of each POSITION accessor this instance has added
  // (primitives sharing an accessor share its vertices).
  absl::Status AddPrimitive(const MeshInstance& instance, size_t p, uint32_t object,
                            std::map<int, std::pair<uint32_t, size_t>>& positions);
  absl::StatusOr<uint32_t> MaterialOf(int material, const std::string& where);
  // Counts the triangles `primitive` draws against kMaxGltfTriangles, before any is made.
  absl::Status ChargeTriangles(const tinygltf::Primitive& primitive, size_t vertex_count,
                               const std::string& where);
  // The vertex indices `primitive` draws (its index accessor's, else 0 .. vertex_count - 1),
  // each checked to be below vertex_count.
  absl::StatusOr<std::vector<uint32_t>> PrimitiveIndices(const tinygltf::Primitive& primitive,
                                                         size_t vertex_count);
  // The primitive's vertices in scene space, appended to the scene; the index of the first.
  absl::StatusOr<uint32_t> AddPositions(int accessor, const Mat4& world, size_t& count);
  // The faces of `triangles` (indices into the primitive's vertices, the first of which is
  // scene vertex `first`), with their texture coordinates from `uv` when it is given.
  absl::Status AddTriangles(const std::vector<Triangle>& triangles, uint32_t first, bool flip,
                            Face prototype, const std::string& where, const PrimitiveUv* uv);
  // The texture coordinates of the primitive's vertices for its material's textures, when
  // the material has textures.
  absl::StatusOr<std::optional<PrimitiveUv>> ReadTexCoords(const tinygltf::Primitive& primitive,
                                                           uint32_t material, size_t vertex_count);

  const tinygltf::Model& model_;
  const std::string& name_;
  const ImportOptions& options_;
  Scene scene_;
  std::map<std::string, uint32_t> object_index_, group_index_;
  std::vector<bool> noted_;  // per glTF material: its losses are in the import log
  std::vector<GltfMaterialTextures> textures_;  // per scene material (none for the default)
  bool textured_ = false;                       // some material has a texture
  std::vector<FaceUv> face_uv_;  // per face while textured_: base colour and emissive sets
  int default_material_ = -1;
  uint64_t triangles_ = 0;
};

absl::Status SceneBuilder::AddMaterials() {
  for (size_t m = 0; m < model_.materials.size(); ++m) {
    absl::StatusOr<Material> material = ConvertMaterial(model_.materials[m], static_cast<int>(m));
    absl::StatusOr<GltfMaterialTextures> textures =
        material.ok() ? ReadGltfMaterialTextures(model_, static_cast<int>(m))
                      : absl::StatusOr<GltfMaterialTextures>(material.status());
    if (!textures.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(name_, ": ", textures.status().message()));
    }
    scene_.materials.push_back(*std::move(material));
    textured_ = textured_ || textures->textures.any();
    textures_.push_back(*std::move(textures));
  }
  return absl::OkStatus();
}

Scene SceneBuilder::Take(const TextureReader& fallback) {
  if (textured_) {
    textures_.resize(scene_.materials.size());  // the default material has none
    std::vector<MaterialTextures> slots;
    for (const GltfMaterialTextures& t : textures_) slots.push_back(t.textures);
    const auto uvs = [this](size_t f, TextureSlot slot) -> const std::vector<TexCoord>& {
      return face_uv_[f][slot == TextureSlot::kEmissive ? 1 : 0];
    };
    ApplyFaceTextures(slots, uvs, GltfImageReader(model_, fallback), kGltfTextureFormat, scene_);
  }
  return std::move(scene_);
}

absl::StatusOr<std::optional<PrimitiveUv>> SceneBuilder::ReadTexCoords(
    const tinygltf::Primitive& primitive, uint32_t material, size_t vertex_count) {
  if (material >= textures_.size() || !textures_[material].textures.any()) return std::nullopt;
  const GltfMaterialTextures& textures = textures_[material];
  PrimitiveUv uv{&textures, {}};
  for (const int set : {textures.base.set, textures.emissive.set}) {
    const auto it = primitive.attributes.find(absl::StrCat("TEXCOORD_", set));
    if (it == primitive.attributes.end() || uv.sets.count(set) > 0) continue;
    absl::StatusOr<std::vector<double>> read = ReadAccessor(model_, it->second, 2);
    if (!read.ok()) return read.status();
    if (read->size() < 2 * vertex_count) {
      return absl::InvalidArgumentError(
          absl::StrCat("TEXCOORD_", set, " has fewer elements than POSITION"));
    }
    uv.sets[set] = *std::move(read);
  }
  return uv;
}

absl::StatusOr<uint32_t> SceneBuilder::MaterialOf(int material, const std::string& where) {
  if (material < 0) {
    if (default_material_ < 0) {
      default_material_ = static_cast<int>(scene_.materials.size());
      scene_.materials.push_back(DefaultMaterial());
    }
    return static_cast<uint32_t>(default_material_);
  }
  if (static_cast<size_t>(material) >= model_.materials.size()) {
    return absl::InvalidArgumentError(
        absl::StrCat(where, ": material ", material, " does not exist"));
  }
  if (!noted_[material]) {
    noted_[material] = true;
    NoteMaterialLosses(model_.materials[material], where, scene_.import_log);
  }
  return static_cast<uint32_t>(material);
}

absl::Status SceneBuilder::AddInstance(const MeshInstance& instance) {
  const tinygltf::Node& node = model_.nodes[instance.node];
  const tinygltf::Mesh& mesh = model_.meshes[instance.mesh];
  const std::string object = !node.name.empty()   ? node.name
                             : !mesh.name.empty() ? mesh.name
                                                  : absl::StrCat("node ", instance.node);
  const uint32_t object_id = InternName(scene_.objects, object_index_, object);
  std::map<int, std::pair<uint32_t, size_t>> positions;  // accessor -> first vertex, count
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    absl::Status added = AddPrimitive(instance, p, object_id, positions);
    if (!added.ok()) return added;
  }
  return absl::OkStatus();
}

absl::Status SceneBuilder::AddPrimitive(const MeshInstance& instance, size_t p, uint32_t object,
                                        std::map<int, std::pair<uint32_t, size_t>>& positions) {
  const tinygltf::Mesh& mesh = model_.meshes[instance.mesh];
  const tinygltf::Primitive& primitive = mesh.primitives[p];
  const std::string mesh_name = mesh.name.empty() ? absl::StrCat("mesh ", instance.mesh)
                                                  : absl::StrCat("mesh '", mesh.name, "'");
  const std::string where = absl::StrCat(name_, ": ", mesh_name, " primitive ", p);
  const auto error = [&](absl::string_view what) {
    return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
  };
  if (!IsSurfaceMode(primitive.mode)) {
    if (primitive.mode < TINYGLTF_MODE_POINTS || primitive.mode > TINYGLTF_MODE_TRIANGLE_FAN) {
      return error(absl::StrCat("unknown mode ", primitive.mode));
    }
    scene_.import_log.Add("gltf_points_lines_skipped",
                          "glTF point and line {primitive|primitives} skipped (no surface)", where);
    return absl::OkStatus();
  }
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) return error("has no POSITION attribute");
  auto added = positions.find(position->second);
  if (added == positions.end()) {
    size_t count = 0;
    absl::StatusOr<uint32_t> first = AddPositions(position->second, instance.world, count);
    if (!first.ok()) return error(first.status().message());
    added = positions.emplace(position->second, std::make_pair(*first, count)).first;
  }
  const auto [first, vertex_count] = added->second;
  if (absl::Status budget = ChargeTriangles(primitive, vertex_count, where); !budget.ok()) {
    return budget;
  }
  absl::StatusOr<std::vector<uint32_t>> indices = PrimitiveIndices(primitive, vertex_count);
  if (!indices.ok()) return error(indices.status().message());
  absl::StatusOr<uint32_t> material = MaterialOf(primitive.material, where);
  if (!material.ok()) return material.status();
  Face prototype;
  prototype.material = *material;
  prototype.object = object;
  const std::string group =
      absl::StrCat(mesh.name.empty() ? absl::StrCat("mesh ", instance.mesh) : mesh.name,
                   mesh.primitives.size() > 1 ? absl::StrCat(" primitive ", p) : "");
  prototype.group = InternName(scene_.groups, group_index_, group);
  absl::StatusOr<std::optional<PrimitiveUv>> uv = ReadTexCoords(primitive, *material, vertex_count);
  if (!uv.ok()) return error(uv.status().message());
  return AddTriangles(AssembleTriangles(primitive.mode, *indices), first,
                      LinearDeterminant(instance.world) < 0, std::move(prototype), where,
                      uv->has_value() ? &**uv : nullptr);
}

absl::Status SceneBuilder::ChargeTriangles(const tinygltf::Primitive& primitive,
                                           size_t vertex_count, const std::string& where) {
  const bool indexed =
      primitive.indices >= 0 && static_cast<size_t>(primitive.indices) < model_.accessors.size();
  const uint64_t drawn = TriangleCount(
      primitive.mode, indexed ? model_.accessors[primitive.indices].count : vertex_count);
  triangles_ += std::min(drawn, kMaxGltfTriangles + 1);  // no wrap-around for absurd counts
  if (triangles_ > kMaxGltfTriangles) {
    return absl::InvalidArgumentError(
        absl::StrCat(where, ": the scene has more than ", kMaxGltfTriangles, " triangles"));
  }
  return absl::OkStatus();
}

absl::StatusOr<std::vector<uint32_t>> SceneBuilder::PrimitiveIndices(
    const tinygltf::Primitive& primitive, size_t vertex_count) {
  std::vector<uint32_t> indices;
  if (primitive.indices == -1) {
    for (size_t v = 0; v < vertex_count; ++v) indices.push_back(static_cast<uint32_t>(v));
    return indices;
  }
  absl::StatusOr<std::vector<uint32_t>> read = ReadIndices(model_, primitive.indices);
  if (!read.ok()) return read.status();
  for (uint32_t index : *read) {
    if (index >= vertex_count) {
      return absl::InvalidArgumentError(
          absl::StrCat("index ", index, " out of range (", vertex_count, " vertices)"));
    }
  }
  return read;
}

absl::StatusOr<uint32_t> SceneBuilder::AddPositions(int accessor, const Mat4& world,
                                                    size_t& count) {
  absl::StatusOr<std::vector<double>> xyz = ReadAccessor(model_, accessor, 3);
  if (!xyz.ok()) return xyz.status();
  count = xyz->size() / 3;
  if (scene_.positions.size() + count > 3 * kMaxGltfTriangles) {
    return absl::InvalidArgumentError(
        absl::StrCat("the scene has more than ", 3 * kMaxGltfTriangles, " vertices"));
  }
  const auto first = static_cast<uint32_t>(scene_.positions.size());
  for (size_t v = 0; v < count; ++v) {
    const Vec3 p = TransformPoint(world, {(*xyz)[3 * v], (*xyz)[3 * v + 1], (*xyz)[3 * v + 2]});
    if (!IsFinite(p)) {
      return absl::InvalidArgumentError(
          absl::StrCat("vertex ", v, " has a NaN or infinite coordinate"));
    }
    scene_.positions.push_back(p);
  }
  return first;
}

absl::Status SceneBuilder::AddTriangles(const std::vector<Triangle>& triangles, uint32_t first,
                                        bool flip, Face prototype, const std::string& where,
                                        const PrimitiveUv* uv) {
  size_t dropped = 0, first_dropped = 0;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Triangle local = flip ? Triangle{triangles[t][0], triangles[t][2], triangles[t][1]}
                                : triangles[t];
    const Triangle v = {local[0] + first, local[1] + first, local[2] + first};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      if (options_.strict) {
        return absl::InvalidArgumentError(
            absl::StrCat(where, ": triangle ", t, " repeats a vertex (zero area)"));
      }
      if (dropped++ == 0) first_dropped = t;
      continue;
    }
    Face face = prototype;
    face.vertices = {v[0], v[1], v[2]};
    scene_.faces.push_back(std::move(face));
    if (textured_) face_uv_.push_back(uv ? uv->Of(local) : FaceUv{});
  }
  if (dropped > 0) {
    scene_.import_log.Add("gltf_repeated_vertex_dropped",
                          "glTF {triangle|triangles} with a repeated vertex (strip restarts) dropped",
                          absl::StrCat(where, " triangle ", first_dropped), dropped);
  }
  return absl::OkStatus();
}

absl::StatusOr<Scene> ModelToScene(const tinygltf::Model& model, const std::string& name,
                                   const ImportOptions& options, const TextureReader& fallback) {
  absl::StatusOr<std::vector<MeshInstance>> instances = FlattenNodes(model);
  if (!instances.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(name, ": ", instances.status().message()));
  }
  SceneBuilder builder(model, name, options);
  if (absl::Status materials = builder.AddMaterials(); !materials.ok()) return materials;
  for (const MeshInstance& instance : *instances) {
    if (absl::Status added = builder.AddInstance(instance); !added.ok()) return added;
  }
  return builder.Take(fallback);
}

}  // namespace

absl::StatusOr<Scene> LoadGltfFile(const std::string& path, const ImportOptions& options) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return absl::NotFoundError(absl::StrCat(path, ": cannot open file"));
  std::ostringstream bytes;
  bytes << file.rdbuf();
  const size_t slash = path.find_last_of('/');
  const std::string base_dir = slash == std::string::npos ? "." : path.substr(0, slash);
  absl::StatusOr<tinygltf::Model> model = ParseGltf(bytes.str(), path, base_dir, nullptr);
  if (!model.ok()) return model.status();
  // An image named with other letter cases than on disk, under the glTF file's folder.
  const TextureReader fallback = [&base_dir](const std::string& uri) -> absl::StatusOr<std::string> {
    if (HasParentStep(uri) || absl::StartsWith(uri, "/")) return absl::NotFoundError("outside the scene's folder");
    return ReadFoundFile(base_dir, uri);
  };
  return ModelToScene(*model, path, options, fallback);
}

absl::StatusOr<Scene> LoadGltfData(const std::string& data, const std::string& name,
                                   const ImportOptions& options,
                                   const std::map<std::string, std::string>& files) {
  absl::StatusOr<tinygltf::Model> model = ParseGltf(data, name, "", &files);
  if (!model.ok()) return model.status();
  const TextureReader fallback = [&files](const std::string& uri) -> absl::StatusOr<std::string> {
    const std::string* bytes = HasParentStep(uri) ? nullptr : FindInFiles(files, uri);
    if (bytes == nullptr) return absl::NotFoundError("no such file in the bundle");
    return *bytes;
  };
  return ModelToScene(*model, name, options, fallback);
}

}  // namespace radflux
