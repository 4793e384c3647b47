#include "solver/output/gltf_writer.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "solver/output/export_mesh.h"
#include "solver/output/gltf_buffers.h"

namespace radflux {
namespace {

struct VertexArrays {
  std::vector<float> positions, normals, colours, radiosity;
  std::vector<double> min, max;
};

VertexArrays BuildVertexArrays(const ExportMesh& mesh, const GltfOptions& options) {
  VertexArrays a;
  a.min.assign(3, std::numeric_limits<double>::infinity());
  a.max.assign(3, -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const float x = static_cast<float>(mesh.positions[i][k] * options.metres_per_unit);
      a.positions.push_back(x);
      a.min[k] = std::min<double>(a.min[k], x);
      a.max[k] = std::max<double>(a.max[k], x);
      a.normals.push_back(static_cast<float>(mesh.normals[i][k]));
      const double b = mesh.radiosity[i][k];
      a.colours.push_back(static_cast<float>(ToneMapLinear(b / std::numbers::pi, options.tone)));
      a.radiosity.push_back(static_cast<float>(b));
    }
  }
  return a;
}

tinygltf::Material UnlitMaterial() {
  tinygltf::Material material;
  material.name = "radflux_baked_radiosity";
  material.pbrMetallicRoughness.baseColorFactor = {1, 1, 1, 1};
  material.pbrMetallicRoughness.metallicFactor = 0;
  material.pbrMetallicRoughness.roughnessFactor = 1;
  material.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
  return material;
}

tinygltf::Model BuildModel(ExportMesh& mesh, const GltfOptions& options) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "radflux";
  model.extensionsUsed.push_back("KHR_materials_unlit");
  model.buffers.emplace_back();
  const std::vector<uint32_t> indices = TriangulateExportMesh(mesh);
  const VertexArrays arrays = BuildVertexArrays(mesh, options);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = 0;
  const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
  primitive.attributes["POSITION"] =
      AddAccessor(model, arrays.positions, TINYGLTF_TYPE_VEC3, target);
  model.accessors.back().minValues = arrays.min;
  model.accessors.back().maxValues = arrays.max;
  primitive.attributes["NORMAL"] = AddAccessor(model, arrays.normals, TINYGLTF_TYPE_VEC3, target);
  primitive.attributes["COLOR_0"] = AddAccessor(model, arrays.colours, TINYGLTF_TYPE_VEC3, target);
  primitive.attributes["_RADIOSITY"] =
      AddAccessor(model, arrays.radiosity, TINYGLTF_TYPE_VEC3, target);
  primitive.indices = AddIndices(model, indices);
  model.materials.push_back(UnlitMaterial());
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "radiosity";
  gltf_mesh.primitives.push_back(primitive);
  model.meshes.push_back(gltf_mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

}  // namespace

absl::Status WriteGlb(const std::string& path, const PatchMesh& mesh, const ShadingMesh& shading,
                      const std::vector<Rgb>& patch_radiosity, const GltfOptions& options) {
  if (mesh.size() == 0) {
    return absl::InvalidArgumentError(absl::StrCat("glTF file '", path, "': the mesh is empty"));
  }
  auto lit = BuildExportMesh(mesh, shading, patch_radiosity);
  if (!lit.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat("glTF file '", path, "': ", lit.status().message()));
  }
  const tinygltf::Model model = BuildModel(*lit, options);
  return WriteGlbModel(path, model);
}

}  // namespace radflux
