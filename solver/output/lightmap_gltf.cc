#include "solver/output/lightmap_gltf.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "solver/output/gltf_buffers.h"
#include "solver/output/lightmap_atlas.h"
#include "solver/output/lightmap_bake.h"
#include "solver/output/vertex_radiosity.h"

namespace radflux {
namespace {

// Vertex arrays and triangles of `mesh` with both UV sets.
void AddGeometry(const PatchMesh& mesh, const LightmapAtlas& atlas, double metres_per_unit,
                 tinygltf::Model& model, tinygltf::Primitive& primitive) {
  const size_t n = mesh.positions.size();
  std::vector<float> positions(3 * n), normals(3 * n), uv0(2 * n), uv1(2 * n);
  std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
  std::vector<uint32_t> indices;
  for (const Patch& patch : mesh.patches) {
    const LightmapChart& chart = atlas.charts[atlas.chart_of_face[patch.face]];
    for (int k = 0; k < patch.VertexCount(); ++k) {
      const uint32_t v = patch.v[k];
      const Vec3& p = mesh.positions[v];
      const Vec3 local = chart.frame.ToLocal(p);
      const Point2 uv = atlas.Uv(chart, p);
      for (int c = 0; c < 3; ++c) {
        positions[3 * v + c] = static_cast<float>(p[c] * metres_per_unit);
        lo[c] = std::min<double>(lo[c], positions[3 * v + c]);
        hi[c] = std::max<double>(hi[c], positions[3 * v + c]);
        normals[3 * v + c] = static_cast<float>(patch.normal[c]);
      }
      uv0[2 * v] = static_cast<float>((local.x - chart.s0) * metres_per_unit);
      uv0[2 * v + 1] = static_cast<float>((local.y - chart.t0) * metres_per_unit);
      uv1[2 * v] = static_cast<float>(uv.x);
      uv1[2 * v + 1] = static_cast<float>(uv.y);
    }
    if (patch.IsTriangle()) {
      indices.insert(indices.end(), {patch.v[0], patch.v[1], patch.v[2]});
    } else {
      indices.insert(indices.end(),
                     {patch.v[0], patch.v[1], patch.v[3], patch.v[2], patch.v[3], patch.v[1]});
    }
  }
  const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
  primitive.attributes["POSITION"] = AddAccessor(model, positions, TINYGLTF_TYPE_VEC3, target);
  model.accessors.back().minValues = lo;
  model.accessors.back().maxValues = hi;
  primitive.attributes["NORMAL"] = AddAccessor(model, normals, TINYGLTF_TYPE_VEC3, target);
  primitive.attributes["TEXCOORD_0"] = AddAccessor(model, uv0, TINYGLTF_TYPE_VEC2, target);
  primitive.attributes["TEXCOORD_1"] = AddAccessor(model, uv1, TINYGLTF_TYPE_VEC2, target);
  primitive.indices = AddIndices(model, indices);
}

// The emissive material on texture 0 (TEXCOORD_1) with strength `strength`.
tinygltf::Material LightmapMaterial(double strength, double radiance_scale) {
  tinygltf::Material material;
  material.name = "radflux_lightmap";
  material.pbrMetallicRoughness.baseColorFactor = {0, 0, 0, 1};
  material.pbrMetallicRoughness.metallicFactor = 0;
  material.pbrMetallicRoughness.roughnessFactor = 1;
  material.emissiveFactor = {1, 1, 1};
  material.emissiveTexture.index = 0;
  material.emissiveTexture.texCoord = 1;
  tinygltf::Value::Object strength_object;
  strength_object["emissiveStrength"] = tinygltf::Value(strength);
  material.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(strength_object);
  tinygltf::Value::Object extras;
  extras["radflux_radiance_scale"] = tinygltf::Value(radiance_scale);
  material.extras = tinygltf::Value(extras);
  return material;
}

// Texture 0: the lightmap PNG in the buffer, linearly filtered, clamped at the edges.
void AddTexture(const std::string& png, tinygltf::Model& model) {
  tinygltf::Image image;
  image.name = "radflux_lightmap";
  image.mimeType = "image/png";
  image.bufferView = AddBufferView(model, png);
  model.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  model.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.source = 0;
  texture.sampler = 0;
  model.textures.push_back(texture);
}

}  // namespace

absl::Status WriteLightmapGlb(const std::string& path, const PatchMesh& mesh,
                              const ShadingMesh& shading, const std::vector<Rgb>& patch_radiosity,
                              int size, const GltfOptions& options) {
  auto fail = [&](const absl::Status& s) {
    return absl::Status(s.code(), absl::StrCat("glTF file '", path, "': ", s.message()));
  };
  absl::StatusOr<LightmapAtlas> atlas = BuildLightmapAtlas(mesh, size);
  if (!atlas.ok()) return fail(atlas.status());
  absl::StatusOr<std::vector<Rgb>> at_vertex = VertexRadiosity(mesh, shading, patch_radiosity);
  if (!at_vertex.ok()) return fail(at_vertex.status());
  const Image radiance = BakeLightmap(mesh, *atlas, *at_vertex);
  const double scale = options.tone.scale * std::exp2(options.tone.exposure_stops);
  double strength = 1;
  for (float value : radiance.rgb) strength = std::max(strength, value * scale);
  ToneMapOptions encode;
  encode.scale = scale / strength;
  absl::StatusOr<std::string> png = EncodePng(radiance, encode);
  if (!png.ok()) return fail(png.status());

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "radflux";
  model.extensionsUsed.push_back("KHR_materials_emissive_strength");
  model.buffers.emplace_back();
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = 0;
  AddGeometry(mesh, *atlas, options.metres_per_unit, model, primitive);
  AddTexture(*png, model);
  model.materials.push_back(LightmapMaterial(strength, scale));
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "radiosity_lightmapped";
  gltf_mesh.primitives.push_back(primitive);
  model.meshes.push_back(gltf_mesh);
  model.nodes.emplace_back().mesh = 0;
  model.scenes.emplace_back().nodes.push_back(0);
  model.defaultScene = 0;
  return WriteGlbModel(path, model);
}

}  // namespace radflux
