// Bounds-checked reads of glTF accessors from a parsed tinygltf model. Every index, offset,
// stride and count is checked against the buffer before a byte is read, so a malformed file
// is an error message, never a read out of bounds (tinygltf itself checks little of this).
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "tiny_gltf.h"

namespace radflux {

// The bytes of bufferView `index`, checked to lie in its buffer. INVALID_ARGUMENT ("has no
// valid bufferView", "... reaches past the end of its buffer") otherwise.
absl::StatusOr<absl::string_view> BufferViewBytes(const tinygltf::Model& model, int index);

// The elements of accessor `index` as doubles, `components` per element (3 for a VEC3),
// element after element. Integer components are converted as glTF says: to [0,1] or [-1,1]
// when the accessor is `normalized`, to their value otherwise. INVALID_ARGUMENT (message
// without the file name) when the accessor is missing, of another type, sparse (not
// supported), without a bufferView, or reaches past its bufferView or buffer.
absl::StatusOr<std::vector<double>> ReadAccessor(const tinygltf::Model& model, int index,
                                                 int components);

// The vertex indices of accessor `index`: SCALAR of unsigned byte, short or int; errors as
// ReadAccessor's.
absl::StatusOr<std::vector<uint32_t>> ReadIndices(const tinygltf::Model& model, int index);

}  // namespace radflux
