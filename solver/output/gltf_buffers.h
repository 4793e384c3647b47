// Writing glTF with tinygltf, shared by the glTF writers: every array goes into buffer 0 as
// its own buffer view (4-byte aligned), and the model is written as one .glb file.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"

namespace radflux {

// Appends float `values` as an accessor of `type` (TINYGLTF_TYPE_SCALAR, VEC2 or VEC3) for
// buffer target `target`; returns the accessor index.
int AddAccessor(tinygltf::Model& model, const std::vector<float>& values, int type, int target);

// Appends triangle indices as an UNSIGNED_INT element-array accessor; returns its index.
int AddIndices(tinygltf::Model& model, const std::vector<uint32_t>& indices);

// Appends raw bytes (an encoded image) as a buffer view; returns the view's index.
int AddBufferView(tinygltf::Model& model, const std::string& bytes);

// Encodes `model` as binary glTF into `path`; the error names the file.
absl::Status WriteGlbModel(const std::string& path, const tinygltf::Model& model);

}  // namespace radflux
