// glTF files written by hand for the loader tests: a small builder of the JSON and its one
// binary buffer, saved as .gltf (buffer as a base64 data URI, or beside it as a .bin) or as
// .glb. Only what the tests need: float VEC3 positions, index accessors, meshes, nodes.
#pragma once

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "absl/strings/escaping.h"

namespace radflux::testing {

class GltfBuilder {
 public:
  GltfBuilder() {
    json_["asset"] = {{"version", "2.0"}};
    for (const char* key : {"bufferViews", "accessors", "meshes", "nodes", "materials"}) {
      json_[key] = nlohmann::json::array();
    }
  }

  // A bufferView of `bytes` appended to the buffer (4-byte aligned); its index.
  int AddView(const std::string& bytes, int stride = 0) {
    while (bin_.size() % 4 != 0) bin_.push_back('\0');
    nlohmann::json view = {
        {"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes.size()}};
    if (stride > 0) view["byteStride"] = stride;
    bin_ += bytes;
    json_["bufferViews"].push_back(view);
    return static_cast<int>(json_["bufferViews"].size()) - 1;
  }

  int AddAccessor(int view, int component_type, size_t count, const std::string& type,
                  size_t byte_offset = 0) {
    json_["accessors"].push_back({{"bufferView", view},
                                  {"componentType", component_type},
                                  {"count", count},
                                  {"type", type},
                                  {"byteOffset", byte_offset}});
    return static_cast<int>(json_["accessors"].size()) - 1;
  }

  // Float VEC3 positions, x y z per vertex.
  int AddPositions(const std::vector<float>& xyz) {
    return AddAccessor(AddView(Bytes(xyz)), 5126, xyz.size() / 3, "VEC3");
  }

  // Indices as unsigned byte (5121), short (5123) or int (5125).
  int AddIndices(const std::vector<uint32_t>& indices, int component_type = 5125) {
    std::string bytes;
    for (uint32_t i : indices) {
      if (component_type == 5121) bytes += Bytes(std::vector<uint8_t>{static_cast<uint8_t>(i)});
      if (component_type == 5123) bytes += Bytes(std::vector<uint16_t>{static_cast<uint16_t>(i)});
      if (component_type == 5125) bytes += Bytes(std::vector<uint32_t>{i});
    }
    return AddAccessor(AddView(bytes), component_type, indices.size(), "SCALAR");
  }

  // A primitive (JSON) with POSITION `positions`, optional indices, mode and material.
  static nlohmann::json Primitive(int positions, int indices = -1, int mode = 4,
                                  int material = -1) {
    nlohmann::json p = {{"attributes", {{"POSITION", positions}}}, {"mode", mode}};
    if (indices >= 0) p["indices"] = indices;
    if (material >= 0) p["material"] = material;
    return p;
  }

  int AddMesh(const std::string& name, const std::vector<nlohmann::json>& primitives) {
    nlohmann::json mesh = {{"primitives", primitives}};
    if (!name.empty()) mesh["name"] = name;
    json_["meshes"].push_back(mesh);
    return static_cast<int>(json_["meshes"].size()) - 1;
  }

  // A node (JSON object with whatever fields the test sets); its index.
  int AddNode(const nlohmann::json& node) {
    json_["nodes"].push_back(node);
    return static_cast<int>(json_["nodes"].size()) - 1;
  }

  int AddMaterial(const nlohmann::json& material) {
    json_["materials"].push_back(material);
    return static_cast<int>(json_["materials"].size()) - 1;
  }

  // The scenes: the listed root nodes as scene 0, the default.
  void SetScene(const std::vector<int>& roots) {
    json_["scenes"] = nlohmann::json::array({{{"nodes", roots}}});
    json_["scene"] = 0;
  }

  nlohmann::json& json() { return json_; }
  const std::string& bin() const { return bin_; }

  // .gltf text with the buffer as a data URI, or named `bin_uri` (an external file).
  std::string Gltf(const std::string& bin_uri = "") const {
    nlohmann::json out = json_;
    out["buffers"] =
        nlohmann::json::array({{{"byteLength", bin_.size()},
                                {"uri", bin_uri.empty() ? "data:application/octet-stream;base64," +
                                                              absl::Base64Escape(bin_)
                                                        : bin_uri}}});
    return out.dump();
  }

  // .glb bytes: header, JSON chunk, BIN chunk, each padded to 4 bytes.
  std::string Glb() const {
    nlohmann::json out = json_;
    out["buffers"] = nlohmann::json::array({{{"byteLength", bin_.size()}}});
    std::string text = out.dump();
    while (text.size() % 4 != 0) text.push_back(' ');
    std::string bin = bin_;
    while (bin.size() % 4 != 0) bin.push_back('\0');
    const uint32_t length = static_cast<uint32_t>(12 + 8 + text.size() + 8 + bin.size());
    return "glTF" + Word(2) + Word(length) + Word(static_cast<uint32_t>(text.size())) + "JSON" +
           text + Word(static_cast<uint32_t>(bin.size())) + std::string("BIN\0", 4) + bin;
  }

  template <typename T>
  static std::string Bytes(const std::vector<T>& values) {
    std::string bytes(values.size() * sizeof(T), '\0');
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
  }

 private:
  static std::string Word(uint32_t value) { return Bytes(std::vector<uint32_t>{value}); }

  nlohmann::json json_;
  std::string bin_;
};

}  // namespace radflux::testing
