#include "solver/scene/scene_references.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "solver/scene/file_lookup.h"
#include "solver/scene/mgf_loader.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

absl::StatusOr<std::string> ReadWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat(path, ": cannot open the file"));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Folder(const std::string& path) { return fs::path(path).parent_path().string(); }

// Appends the file `name` names from `dir`, when it is on disk and not listed yet.
void Add(const std::string& dir, const std::string& name, std::vector<std::string>& files) {
  if (name.empty()) return;
  const std::optional<std::string> found = FindFile(dir, name);
  if (found && std::find(files.begin(), files.end(), *found) == files.end()) {
    files.push_back(*found);
  }
}

// The textures an MTL file names, relative to the OBJ's folder `dir` (as tinyobjloader
// reads them, and the OBJ loader after it).
void AddMtlTextures(const std::string& mtl_path, const std::string& dir,
                    std::vector<std::string>& files) {
  std::ifstream in(mtl_path, std::ios::binary);
  std::map<std::string, int> names;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  tinyobj::LoadMtl(&names, &materials, &in, &warning, &error);
  for (const tinyobj::material_t& m : materials) {
    for (const std::string* texture : {&m.diffuse_texname, &m.emissive_texname, &m.alpha_texname}) {
      Add(dir, *texture, files);
    }
  }
}

void AddObjReferences(const std::string& path, const std::string& text,
                      std::vector<std::string>& files) {
  for (absl::string_view line : absl::StrSplit(text, '\n')) {
    line = absl::StripAsciiWhitespace(line);
    if (!absl::StartsWith(line, "mtllib") || line.size() < 7 || !absl::ascii_isspace(line[6])) {
      continue;
    }
    for (absl::string_view name : absl::StrSplit(line.substr(7), ' ', absl::SkipWhitespace())) {
      const size_t before = files.size();
      Add(Folder(path), std::string(absl::StripAsciiWhitespace(name)), files);
      if (files.size() > before) AddMtlTextures(files.back(), Folder(path), files);
    }
  }
}

// `uri` with its %XX escapes decoded.
std::string DecodeUri(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && absl::ascii_isxdigit(uri[i + 1]) &&
        absl::ascii_isxdigit(uri[i + 2])) {
      out.push_back(static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

// The JSON of a .gltf, or of a .glb's first chunk (told apart by the GLB header).
std::string GltfJson(const std::string& bytes) {
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return bytes;
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, sizeof(length));
  return bytes.substr(20, std::min<size_t>(length, bytes.size() - 20));
}

void AddGltfReferences(const std::string& path, const std::string& bytes,
                       std::vector<std::string>& files) {
  const nlohmann::json json = nlohmann::json::parse(GltfJson(bytes), nullptr, false);
  if (!json.is_object()) return;  // the loader says what is wrong
  for (const char* key : {"buffers", "images"}) {
    if (!json.contains(key) || !json[key].is_array()) continue;
    for (const nlohmann::json& item : json[key]) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (!absl::StartsWith(uri, "data:")) Add(Folder(path), DecodeUri(uri), files);
    }
  }
}

absl::Status AddMgfIncludes(const std::string& path, const std::string& text,
                            std::vector<std::string>& files) {
  const MgfFileReader reader = [&](const std::string& include) {
    absl::StatusOr<std::string> data = ReadWhole(include);
    if (data.ok()) Add("", include, files);
    return data;
  };
  return LoadMgfText(text, path, ImportOptions{}, reader).status();
}

}  // namespace

absl::StatusOr<std::vector<std::string>> SceneReferences(const std::string& path) {
  absl::StatusOr<std::string> text = ReadWhole(path);
  if (!text.ok()) return text.status();
  const std::string ext = absl::AsciiStrToLower(fs::path(path).extension().string());
  std::vector<std::string> files;
  if (ext == ".obj") AddObjReferences(path, *text, files);
  if (ext == ".gltf" || ext == ".glb") AddGltfReferences(path, *text, files);
  if (ext == ".stl") Add(Folder(path), fs::path(path).filename().string() + ".groups", files);
  if (ext == ".mgf") {
    if (absl::Status s = AddMgfIncludes(path, *text, files); !s.ok()) return s;
  }
  return files;
}

}  // namespace radflux
