#include "solver/scene/gltf_accessor.h"

#include <algorithm>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

// Where an accessor's elements are: `count` elements of `element` bytes, `stride` apart,
// the first at `data`. Only made by Locate, which checks that all of them lie in the buffer.
struct Span {
  const unsigned char* data = nullptr;
  size_t count = 0, stride = 0;
  int component_type = 0;
};

// Bytes of one component of `component_type`, 0 for an unknown type.
size_t ComponentBytes(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

absl::Status AccessorError(int index, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat("accessor ", index, ": ", what));
}

absl::StatusOr<Span> Locate(const tinygltf::Model& model, int index, int components) {
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) {
    return absl::InvalidArgumentError(absl::StrCat("accessor ", index, " does not exist"));
  }
  const tinygltf::Accessor& accessor = model.accessors[index];
  if (accessor.sparse.isSparse) return AccessorError(index, "sparse accessors are not supported");
  if (tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type)) != components) {
    return AccessorError(index, absl::StrCat("expected ", components, " components per element"));
  }
  const size_t component = ComponentBytes(accessor.componentType);
  if (component == 0) return AccessorError(index, "unknown componentType");
  absl::StatusOr<absl::string_view> bytes = BufferViewBytes(model, accessor.bufferView);
  if (!bytes.ok()) return AccessorError(index, std::string(bytes.status().message()));
  const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
  const size_t element = component * static_cast<size_t>(components);
  const size_t stride = view.byteStride == 0 ? element : view.byteStride;
  if (stride < element) return AccessorError(index, "byteStride is smaller than an element");
  Span span{reinterpret_cast<const unsigned char*>(bytes->data()), accessor.count, stride,
            accessor.componentType};
  if (accessor.count == 0) return span;
  // The last element ends at byteOffset + stride * (count - 1) + element <= byteLength,
  // checked without overflow.
  const size_t length = bytes->size();
  if (accessor.byteOffset > length || element > length - accessor.byteOffset ||
      accessor.count - 1 > (length - accessor.byteOffset - element) / stride) {
    return AccessorError(index, "reaches past the end of its bufferView");
  }
  span.data += accessor.byteOffset;
  return span;
}

template <typename T>
T Load(const unsigned char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

// Component `k` of element `i`, as glTF's normalisation rules say when `normalized`.
double Component(const Span& span, size_t i, int k, bool normalized) {
  const unsigned char* p = span.data + i * span.stride + k * ComponentBytes(span.component_type);
  switch (span.component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return normalized ? std::max(Load<int8_t>(p) / 127.0, -1.0) : Load<int8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? Load<uint8_t>(p) / 255.0 : Load<uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return normalized ? std::max(Load<int16_t>(p) / 32767.0, -1.0) : Load<int16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return normalized ? Load<uint16_t>(p) / 65535.0 : Load<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return normalized ? Load<uint32_t>(p) / 4294967295.0 : Load<uint32_t>(p);
    default:
      return Load<float>(p);
  }
}

}  // namespace

absl::StatusOr<absl::string_view> BufferViewBytes(const tinygltf::Model& model, int index) {
  if (index < 0 || static_cast<size_t>(index) >= model.bufferViews.size()) {
    return absl::InvalidArgumentError("has no valid bufferView");
  }
  const tinygltf::BufferView& view = model.bufferViews[index];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
    return absl::InvalidArgumentError("its bufferView names no valid buffer");
  }
  const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
    return absl::InvalidArgumentError("its bufferView reaches past the end of its buffer");
  }
  return absl::string_view(reinterpret_cast<const char*>(buffer.data()) + view.byteOffset,
                           view.byteLength);
}

absl::StatusOr<std::vector<double>> ReadAccessor(const tinygltf::Model& model, int index,
                                                 int components) {
  absl::StatusOr<Span> span = Locate(model, index, components);
  if (!span.ok()) return span.status();
  const bool normalized = model.accessors[index].normalized;
  std::vector<double> values;
  values.reserve(span->count * components);
  for (size_t i = 0; i < span->count; ++i) {
    for (int k = 0; k < components; ++k) values.push_back(Component(*span, i, k, normalized));
  }
  return values;
}

absl::StatusOr<std::vector<uint32_t>> ReadIndices(const tinygltf::Model& model, int index) {
  absl::StatusOr<Span> span = Locate(model, index, 1);
  if (!span.ok()) return span.status();
  const int type = span->component_type;
  if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    return AccessorError(index, "indices must be unsigned byte, short or int");
  }
  std::vector<uint32_t> indices(span->count);
  const auto copy = [&](auto zero) {
    for (size_t i = 0; i < span->count; ++i) {
      indices[i] = Load<decltype(zero)>(span->data + i * span->stride);
    }
  };
  if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) copy(uint8_t{0});
  if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) copy(uint16_t{0});
  if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) copy(uint32_t{0});
  return indices;
}

}  // namespace radflux
