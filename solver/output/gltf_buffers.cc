#include "solver/output/gltf_buffers.h"

#include <cstring>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "solver/output/output_file.h"

namespace radflux {
namespace {

int AddView(tinygltf::Model& model, const void* bytes, size_t length, int target) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4);  // every view starts 4-byte aligned
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = length;
  view.target = target;
  data.resize(data.size() + length);
  std::memcpy(data.data() + view.byteOffset, bytes, length);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

}  // namespace

int AddAccessor(tinygltf::Model& model, const std::vector<float>& values, int type, int target) {
  tinygltf::Accessor accessor;
  accessor.bufferView = AddView(model, values.data(), values.size() * sizeof(float), target);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.type = type;
  const size_t components = type == TINYGLTF_TYPE_VEC3 ? 3 : (type == TINYGLTF_TYPE_VEC2 ? 2 : 1);
  accessor.count = values.size() / components;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

int AddIndices(tinygltf::Model& model, const std::vector<uint32_t>& indices) {
  tinygltf::Accessor accessor;
  accessor.bufferView = AddView(model, indices.data(), indices.size() * sizeof(uint32_t),
                                TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  accessor.type = TINYGLTF_TYPE_SCALAR;
  accessor.count = indices.size();
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

int AddBufferView(tinygltf::Model& model, const std::string& bytes) {
  return AddView(model, bytes.data(), bytes.size(), 0);
}

absl::Status WriteGlbModel(const std::string& path, const tinygltf::Model& model) {
  std::ostringstream stream;
  tinygltf::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&model, stream, false, true)) {
    return absl::InternalError(absl::StrCat("cannot encode glTF file '", path, "'"));
  }
  return WriteOutputFile(path, stream.str(), "glTF");
}

}  // namespace radflux
