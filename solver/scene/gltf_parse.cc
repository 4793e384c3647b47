#include "solver/scene/gltf_parse.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <map>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"

namespace radflux {
namespace {

// Extensions a file may require and still load right: the material extensions (a diffuse
// solve reads base colour and emission only; emissive strength is read), texture transforms
// (read, gltf_textures.h) and quantized vertex attributes (the accessor reader handles any
// component type). Compressed geometry (Draco, meshopt) is refused.
bool Readable(const std::string& extension) {
  return absl::StartsWith(extension, "KHR_materials_") || extension == "KHR_texture_transform" ||
         extension == "KHR_mesh_quantization";
}

// Fs callbacks' user data: where external files may come from.
struct FileAccess {
  std::string base_dir;                                       // on disk, under this ("" = not)
  const std::map<std::string, std::string>* files = nullptr;  // or these (relative path -> bytes)
};

// The bytes `path` names in access.files, or null (the path as tinygltf joins it to an
// empty base directory: the URI itself).
const std::string* BundleFile(const std::string& path, const FileAccess& access) {
  if (access.files == nullptr || HasParentStep(path)) return nullptr;
  const auto it = access.files->find(path);
  return it == access.files->end() ? nullptr : &it->second;
}

// Whether `path` may be read from disk: under base_dir, no ".." component.
bool OnDiskUnderBaseDir(const std::string& path, const FileAccess& access) {
  return !access.base_dir.empty() && absl::StartsWith(path, access.base_dir) &&
         !HasParentStep(path);
}

bool FileExists(const std::string& path, void* user_data) {
  const FileAccess& access = *static_cast<FileAccess*>(user_data);
  if (access.files != nullptr) return BundleFile(path, access) != nullptr;
  struct stat info;
  return OnDiskUnderBaseDir(path, access) && stat(path.c_str(), &info) == 0 &&
         S_ISREG(info.st_mode);
}

std::string ExpandFilePath(const std::string& path, void*) { return path; }

bool ReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user_data) {
  const FileAccess& access = *static_cast<FileAccess*>(user_data);
  if (const std::string* bytes = BundleFile(path, access); bytes != nullptr) {
    out->assign(bytes->begin(), bytes->end());
    return true;
  }
  struct stat info;
  if (!OnDiskUnderBaseDir(path, access) || stat(path.c_str(), &info) != 0) {
    *err = "not readable here";
    return false;
  }
  if (static_cast<uint64_t>(info.st_size) > kMaxGltfExternalBytes) {
    *err = absl::StrCat("larger than ", kMaxGltfExternalBytes, " bytes");
    return false;
  }
  std::ifstream file(path, std::ios::binary);
  out->resize(static_cast<size_t>(info.st_size));
  if (!file.read(reinterpret_cast<char*>(out->data()), info.st_size)) {
    *err = "read failed";
    return false;
  }
  return true;
}

bool WriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&,
                    void*) {
  *err = "radflux does not write glTF files while loading";
  return false;
}

// Images are not decoded here: the bytes of an image file (an external file or a data URI)
// are kept in Image::image for the texture reader (gltf_textures.h). An image in a
// bufferView is left alone: tinygltf does not check that view against its buffer, so its
// bytes are read later through BufferViewBytes, which does.
bool KeepImageBytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                    const unsigned char* bytes, int size, void*) {
  if (image->bufferView == -1 && bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

// tinygltf's messages (several lines, trailing newlines) as one line.
std::string OneLine(const std::string& text) {
  std::vector<std::string> lines = absl::StrSplit(text, absl::ByAnyChar("\r\n"), absl::SkipEmpty());
  return absl::StrJoin(lines, "; ");
}

// The deepest nesting of arrays and objects in JSON `text` (strings skipped).
int NestingDepth(absl::string_view text) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

// The JSON text of `data`: all of it, or a GLB's JSON chunk (as far as `data` holds it).
absl::string_view JsonText(const std::string& data, bool binary) {
  if (!binary) return data;
  if (data.size() < 20) return {};
  uint32_t length;
  std::memcpy(&length, data.data() + 12, 4);
  return absl::string_view(data).substr(20, length);
}

absl::Status RequiredExtensionsReadable(const tinygltf::Model& model, const std::string& name) {
  for (const std::string& extension : model.extensionsRequired) {
    if (!Readable(extension)) {
      return absl::InvalidArgumentError(absl::StrCat(name, ": requires glTF extension '", extension,
                                                     "', which radflux does not read"));
    }
  }
  return absl::OkStatus();
}

}  // namespace

bool HasParentStep(const std::string& path) {
  for (absl::string_view part : absl::StrSplit(path, '/')) {
    if (part == "..") return true;
  }
  return false;
}

absl::StatusOr<tinygltf::Model> ParseGltf(const std::string& data, const std::string& name,
                                          const std::string& base_dir,
                                          const std::map<std::string, std::string>* files) {
  if (data.size() > std::numeric_limits<unsigned int>::max()) {
    return absl::InvalidArgumentError(absl::StrCat(name, ": larger than 4 GiB"));
  }
  const bool binary = absl::StartsWith(data, "glTF");
  // tinygltf reads nested JSON values recursively: deep nesting would overflow the stack.
  if (NestingDepth(JsonText(data, binary)) > kMaxGltfJsonDepth) {
    return absl::InvalidArgumentError(absl::StrCat(
        name, ": cannot parse glTF: JSON nested deeper than ", kMaxGltfJsonDepth, " levels"));
  }
  FileAccess access{files == nullptr ? base_dir : "", files};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&FileExists, &ExpandFilePath, &ReadWholeFile, &WriteWholeFile, &access});
  loader.SetImageLoader(&KeepImageBytes, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    const auto size = static_cast<unsigned int>(data.size());
    ok = binary
             ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                           reinterpret_cast<const unsigned char*>(data.data()),
                                           size, access.base_dir)
             : loader.LoadASCIIFromString(&model, &err, &warn, data.data(), size, access.base_dir);
  } catch (const std::exception& e) {
    err = e.what();
    ok = false;
  }
  if (!ok) {
    return absl::InvalidArgumentError(absl::StrCat(
        name, ": cannot parse glTF: ", err.empty() ? "no reason given" : OneLine(err)));
  }
  if (absl::Status readable = RequiredExtensionsReadable(model, name); !readable.ok()) {
    return readable;
  }
  return model;
}

}  // namespace radflux
