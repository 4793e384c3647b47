#include "solver/scene/obj_loader.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string_view>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "solver/scene/file_lookup.h"
#include "solver/scene/mtl_check.h"
#include "tiny_obj_loader.h"

namespace radflux {
namespace {

// The wrap modes of an MTL texture: its edges stretch on under `-clamp on`, else it repeats.
TextureWrapping ObjWrapping(const tinyobj::texture_option_t& option) {
  if (!option.clamp) return {};
  return {TextureWrap::kClampToEdge, TextureWrap::kClampToEdge};
}

// Where each 'f' statement stands in the file and which 'o', 'g' and 'usemtl' are
// in force there. tinyobjloader parses the geometry; this scan only recovers the
// provenance that it does not keep, so that messages and results can name surfaces,
// the material libraries named, and the first line tinyobjloader would misread silently:
// a vertex coordinate that is NaN or infinite (read as 0) or a face index beyond 32 bits
// (2^63 + 1 wraps to a valid vertex).
struct FaceOrigin {
  int line = 0;
  std::string object, group, usemtl;
};

struct SourceScan {
  std::vector<FaceOrigin> faces;
  std::vector<std::string> libraries;  // the words of the 'mtllib' lines, in order
  int bad_line = 0;                    // the first line misread silently, 0 if none
  std::string bad_what;                // what is wrong on it
};

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// The words of `line` after its keyword: leading blanks and trailing blanks dropped.
std::string_view Rest(std::string_view line) {
  while (!line.empty() && IsBlank(line.front())) line.remove_prefix(1);
  while (!line.empty() && IsBlank(line.back())) line.remove_suffix(1);
  return line;
}

// Whether one of the first three numbers of a 'v' line is NaN or infinite (strtod is only
// called when a letter that such a number needs appears: most lines never pay for it).
bool HasNonFiniteCoordinate(std::string_view rest) {
  if (rest.find_first_of("nNiIeE") == std::string_view::npos) return false;
  const std::string words(rest);
  const char* p = words.c_str();
  for (int k = 0; k < 3; ++k) {
    char* end = nullptr;
    const double value = std::strtod(p, &end);
    if (end == p) return false;
    if (!std::isfinite(value)) return true;
    p = end;
  }
  return false;
}

// The first index of an 'f' line's `rest` (its "v/vt/vn" words) that does not fit the
// loader's int, as written; "" when all fit.
std::string_view OversizedIndex(std::string_view rest) {
  size_t at = 0;
  while (at < rest.size()) {
    while (at < rest.size() && (IsBlank(rest[at]) || rest[at] == '/')) ++at;
    size_t end = at;
    while (end < rest.size() && !IsBlank(rest[end]) && rest[end] != '/') ++end;
    int value = 0;
    if (std::from_chars(rest.data() + at, rest.data() + end, value).ec ==
        std::errc::result_out_of_range) {
      return rest.substr(at, end - at);
    }
    at = end;
  }
  return {};
}

// Notes the first line misread silently, `what` being wrong on it.
void NoteBadLine(SourceScan& scan, int line, std::string what) {
  if (scan.bad_line != 0) return;
  scan.bad_line = line;
  scan.bad_what = std::move(what);
}

SourceScan ScanSource(const std::string& text) {
  SourceScan scan;
  FaceOrigin current;
  size_t start = 0;
  for (int number = 1; start < text.size(); ++number) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    while (!line.empty() && IsBlank(line.front())) line.remove_prefix(1);
    size_t word = 0;
    while (word < line.size() && !IsBlank(line[word])) ++word;
    const std::string_view keyword = line.substr(0, word);
    if (keyword == "f") {
      current.line = number;
      scan.faces.push_back(current);
      if (const std::string_view index = OversizedIndex(line.substr(word)); !index.empty()) {
        NoteBadLine(scan, number, absl::StrCat("face index ", std::string(index), " is out of range"));
      }
    } else if (keyword == "v") {
      if (HasNonFiniteCoordinate(line.substr(word))) {
        NoteBadLine(scan, number, "vertex has a NaN or infinite coordinate");
      }
    } else if (keyword == "mtllib") {
      const std::string_view names = Rest(line.substr(word));
      for (absl::string_view name : absl::StrSplit(absl::string_view(names.data(), names.size()),
                                                   absl::ByAnyChar(" \t"), absl::SkipEmpty())) {
        scan.libraries.emplace_back(name);
      }
    } else if (keyword == "o") {
      current.object = Rest(line.substr(word));
    } else if (keyword == "g") {
      current.group = Rest(line.substr(word));
    } else if (keyword == "usemtl") {
      current.usemtl = Rest(line.substr(word));
    }
  }
  return scan;
}

constexpr uint32_t kNone = 0xffffffffu;

// InternName, skipping the lookup when `name` is the name interned last (`last`): faces
// come in runs of one object and group.
uint32_t Intern(std::vector<std::string>& names, std::map<std::string, uint32_t>& index,
                const std::string& name, uint32_t& last) {
  if (last != kNone && names[last] == name) return last;
  last = InternName(names, index, name);
  return last;
}

// tinyobjloader's warnings (e.g. a missing .mtl file) on one line, as " (a; b)".
std::string LoaderNotes(const std::string& warnings) {
  std::string notes;
  std::istringstream lines(warnings);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty()) notes += (notes.empty() ? "" : "; ") + line;
  }
  return notes.empty() ? "" : " (" + notes + ")";
}

// The texture coordinates of the `arity` vertices from `offset` of `mesh`, or none when one
// of them has none.
std::vector<TexCoord> FaceTexCoords(const tinyobj::attrib_t& attrib, const tinyobj::mesh_t& mesh,
                                    size_t offset, size_t arity) {
  std::vector<TexCoord> uv;
  for (size_t k = 0; k < arity; ++k) {
    const int t = mesh.indices[offset + k].texcoord_index;
    if (t < 0 || 2 * static_cast<size_t>(t) + 1 >= attrib.texcoords.size()) return {};
    uv.push_back({attrib.texcoords[2 * t], attrib.texcoords[2 * t + 1]});
  }
  return uv;
}

// The scan of `obj_text`, or INVALID_ARGUMENT "NAME:LINE: what" for its first line that
// tinyobjloader would misread silently.
absl::StatusOr<SourceScan> CheckedScan(const std::string& obj_text, const std::string& name) {
  SourceScan scan = ScanSource(obj_text);
  if (scan.bad_line > 0) {
    return absl::InvalidArgumentError(absl::StrCat(name, ":", scan.bad_line, ": ", scan.bad_what));
  }
  return scan;
}

// What tinyobjloader read (ObjReader's fields), from a file or from memory.
struct ParsedObj {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning;
  std::string error;
  bool valid = false;
};

// A read-only streambuf over pieces of memory, one after another, not copied (an
// uploaded OBJ may be hundreds of MB: ObjReader::ParseFromString copied it).
class PiecesBuf final : public std::streambuf {
 public:
  explicit PiecesBuf(std::vector<std::string_view> pieces) : pieces_(std::move(pieces)) {}

 protected:
  int_type underflow() override {
    while (gptr() == egptr()) {
      if (next_ == pieces_.size()) return traits_type::eof();
      const std::string_view piece = pieces_[next_++];
      char* begin = const_cast<char*>(piece.data());  // only read through get pointers
      setg(begin, begin, begin + piece.size());
    }
    return traits_type::to_int_type(*gptr());
  }

 private:
  std::vector<std::string_view> pieces_;
  size_t next_ = 0;
};

absl::StatusOr<Scene> ConvertReader(const ParsedObj& reader, const SourceScan& scan,
                                    const std::string& name, const TextureReader& textures) {
  if (!reader.valid) {
    return absl::InvalidArgumentError(absl::StrCat(name, ": cannot parse OBJ: ", reader.error));
  }
  Scene scene;
  scene.source = name;
  const auto& attrib = reader.attrib;
  const size_t vertex_count = attrib.vertices.size() / 3;
  for (size_t v = 0; v < vertex_count; ++v) {
    scene.positions.push_back(
        {attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]});
  }
  std::vector<MaterialTextures> texture_names;
  bool textured = false;
  for (const auto& m : reader.materials) {
    texture_names.push_back({m.diffuse_texname, m.emissive_texname, m.alpha_texname});
    MaterialTextures& wrap = texture_names.back();  // `-clamp on`: the edges stretch on
    wrap.diffuse_wrap = ObjWrapping(m.diffuse_texopt);
    wrap.emissive_wrap = ObjWrapping(m.emissive_texopt);
    wrap.alpha_wrap = ObjWrapping(m.alpha_texopt);
    textured = textured || texture_names.back().any();
    Material material;
    material.name = m.name;
    for (int b = 0; b < kBands; ++b) {
      material.reflectance[b] = m.diffuse[b];
      material.emission[b] = std::numbers::pi * m.emission[b];
    }
    scene.materials.push_back(material);
  }

  const std::vector<FaceOrigin>& origins = scan.faces;
  std::map<std::string, uint32_t> object_index, group_index;
  uint32_t last_object = kNone, last_group = kNone;
  size_t face_number = 0;
  std::vector<std::vector<TexCoord>> uvs;  // per face, kept when a material has a texture
  for (const auto& shape : reader.shapes) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face_number) {
      const size_t arity = shape.mesh.num_face_vertices[f];
      FaceOrigin origin;
      origin.object = origin.group = shape.name;
      if (face_number < origins.size()) origin = origins[face_number];
      Face face;
      face.source_line = origin.line;
      face.object = Intern(scene.objects, object_index, origin.object, last_object);
      face.group = Intern(scene.groups, group_index, origin.group, last_group);
      for (size_t k = 0; k < arity; ++k) {
        const int v = shape.mesh.indices[offset + k].vertex_index;
        if (v < 0 || static_cast<size_t>(v) >= vertex_count) {
          return absl::InvalidArgumentError(
              absl::StrCat(name, ":", origin.line, ": vertex index out of range"));
        }
        face.vertices.push_back(static_cast<uint32_t>(v));
      }
      offset += arity;
      const int material = shape.mesh.material_ids[f];
      if (material < 0 || static_cast<size_t>(material) >= scene.materials.size()) {
        const std::string why = origin.usemtl.empty()
                                    ? "face has no material (no 'usemtl' before it)"
                                    : absl::StrCat("unknown material '", origin.usemtl, "'");
        return absl::InvalidArgumentError(
            absl::StrCat(name, ":", origin.line, ": ", why, LoaderNotes(reader.warning)));
      }
      face.material = static_cast<uint32_t>(material);
      scene.faces.push_back(std::move(face));
      if (textured) uvs.push_back(FaceTexCoords(attrib, shape.mesh, offset - arity, arity));
    }
  }
  if (textured) {
    ApplyFaceTextures(
        texture_names, [&uvs](size_t f, TextureSlot) -> const std::vector<TexCoord>& { return uvs[f]; },
        textures, kObjTextureFormat, scene);
  }
  return scene;
}

}  // namespace

absl::StatusOr<Scene> LoadObjFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return absl::NotFoundError(absl::StrCat(path, ": cannot open file"));
  std::ostringstream text;
  text << file.rdbuf();
  absl::StatusOr<SourceScan> scan = CheckedScan(text.str(), path);
  if (!scan.ok()) return scan.status();
  const size_t slash = path.find_last_of('/');
  const std::string mtl_search_path = slash == std::string::npos ? "./" : path.substr(0, slash + 1);
  const std::string folder = path.substr(0, slash == std::string::npos ? 0 : slash);
  for (const std::string& library : scan->libraries) {
    // A library that cannot be read is left to tinyobjloader's warning, as before.
    const absl::StatusOr<std::string> mtl = ReadFoundFile(folder, library);
    if (!mtl.ok()) continue;
    if (absl::Status s = CheckMtlColours(*mtl, mtl_search_path + library); !s.ok()) return s;
  }
  ParsedObj reader;  // faces as written (not triangulated), no vertex colours
  reader.valid = tinyobj::LoadObj(&reader.attrib, &reader.shapes, &reader.materials,
                                  &reader.warning, &reader.error, path.c_str(),
                                  mtl_search_path.c_str(), false, false);
  const TextureReader textures = [&](const std::string& texture) {
    return ReadFoundFile(folder, texture);
  };
  return ConvertReader(reader, *scan, path, textures);
}

absl::StatusOr<Scene> LoadObjText(const std::string& obj_text, const std::string& mtl_text,
                                  const std::string& name, const TextureReader& textures) {
  absl::StatusOr<SourceScan> scan = CheckedScan(obj_text, name);
  if (!scan.ok()) return scan.status();
  // The MTL is named as the OBJ names it (its first library; scene.mtl when none is named).
  const std::string mtl_name = scan->libraries.empty() ? "scene.mtl" : scan->libraries[0];
  if (absl::Status s = CheckMtlColours(mtl_text, mtl_name); !s.ok()) return s;
  // tinyobjloader reads the MTL text only when the OBJ names a material library.
  const bool names_library = obj_text.find("mtllib") != std::string::npos;
  PiecesBuf obj_buf({names_library ? "" : "mtllib scene.mtl\n", obj_text});
  PiecesBuf mtl_buf({mtl_text});
  std::istream obj_in(&obj_buf);
  std::istream mtl_in(&mtl_buf);
  tinyobj::MaterialStreamReader mtl_reader(mtl_in);
  ParsedObj reader;  // faces as written (not triangulated), no vertex colours
  reader.valid = tinyobj::LoadObj(&reader.attrib, &reader.shapes, &reader.materials,
                                  &reader.warning, &reader.error, &obj_in, &mtl_reader, false,
                                  false);
  const TextureReader none = [](const std::string&) -> absl::StatusOr<std::string> {
    return absl::NotFoundError("no texture files given with this OBJ text");
  };
  return ConvertReader(reader, *scan, name, textures ? textures : none);
}

}  // namespace radflux
