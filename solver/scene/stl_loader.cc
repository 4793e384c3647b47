#include "solver/scene/stl_loader.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

constexpr size_t kBinaryHeaderBytes = 84;  // 80-byte header + uint32 facet count
constexpr size_t kBinaryFacetBytes = 50;   // normal, 3 vertices (12 floats), uint16 attribute

// Whitespace-separated words of a text with the line each is on.
class WordReader {
 public:
  WordReader(const std::string& text, std::string name) : text_(text), name_(std::move(name)) {}

  // The next word, or "" at the end of the text.
  std::string Next() {
    while (pos_ < text_.size() && absl::ascii_isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_++] == '\n') ++line_;
    }
    const size_t start = pos_;
    while (pos_ < text_.size() && !absl::ascii_isspace(static_cast<unsigned char>(text_[pos_]))) {
      ++pos_;
    }
    return text_.substr(start, pos_ - start);
  }
  // Skips the rest of the current line (a solid's name).
  void SkipLine() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  }
  int line() const { return line_; }
  absl::Status Error(const std::string& what) const {
    return absl::InvalidArgumentError(absl::StrCat(name_, ":", line_, ": ", what));
  }
  // Reads `word` (case-insensitively) or fails naming what was found.
  absl::Status Expect(const std::string& word) {
    const std::string got = Next();
    if (absl::EqualsIgnoreCase(got, word)) return absl::OkStatus();
    return Error(absl::StrCat("expected '", word, "', found ",
                              got.empty() ? "the end of the file" : "'" + got + "'"));
  }
  absl::StatusOr<Vec3> ReadVec3(const char* what) {
    double v[3];
    for (double& x : v) {
      const std::string word = Next();
      if (!absl::SimpleAtod(word, &x)) {
        return Error(absl::StrCat("bad ", what, " coordinate '", word, "'"));
      }
    }
    return Vec3{v[0], v[1], v[2]};
  }

 private:
  const std::string& text_;
  std::string name_;
  size_t pos_ = 0;
  int line_ = 1;
};

void AddTriangle(Scene& scene, const Vec3 (&v)[3], int line) {
  Face face;
  for (const Vec3& p : v) {
    face.vertices.push_back(static_cast<uint32_t>(scene.positions.size()));
    scene.positions.push_back(p);
  }
  face.source_line = line;
  scene.faces.push_back(std::move(face));
}

// One "facet normal ... endfacet" after its "facet" word.
absl::Status ReadAsciiFacet(WordReader& words, Scene& scene) {
  const int line = words.line();
  if (absl::Status s = words.Expect("normal"); !s.ok()) return s;
  if (absl::StatusOr<Vec3> normal = words.ReadVec3("normal"); !normal.ok()) {
    return normal.status();
  }
  if (absl::Status s = words.Expect("outer"); !s.ok()) return s;
  if (absl::Status s = words.Expect("loop"); !s.ok()) return s;
  Vec3 v[3];
  for (Vec3& p : v) {
    if (absl::Status s = words.Expect("vertex"); !s.ok()) return s;
    absl::StatusOr<Vec3> read = words.ReadVec3("vertex");
    if (!read.ok()) return read.status();
    p = *read;
  }
  if (absl::Status s = words.Expect("endloop"); !s.ok()) {
    return words.Error("a facet must have exactly 3 vertices (expected 'endloop')");
  }
  if (absl::Status s = words.Expect("endfacet"); !s.ok()) return s;
  AddTriangle(scene, v, line);
  return absl::OkStatus();
}

absl::Status ReadAscii(const std::string& text, const std::string& name, Scene& scene) {
  WordReader words(text, name);
  if (absl::Status s = words.Expect("solid"); !s.ok()) return s;
  words.SkipLine();
  for (bool in_solid = true;;) {
    const std::string word = absl::AsciiStrToLower(words.Next());
    if (word.empty()) {
      if (in_solid) return words.Error("missing 'endsolid' at the end of the file");
      return absl::OkStatus();
    }
    if (in_solid && word == "facet") {
      if (absl::Status s = ReadAsciiFacet(words, scene); !s.ok()) return s;
    } else if (in_solid && word == "endsolid") {
      words.SkipLine();
      in_solid = false;
    } else if (!in_solid && word == "solid") {
      words.SkipLine();
      in_solid = true;
    } else {
      return words.Error(absl::StrCat("unexpected '", word, "' (expected ",
                                      in_solid ? "'facet' or 'endsolid'" : "'solid'", ")"));
    }
  }
}

float ReadFloat(const char* p) {
  float f;
  std::memcpy(&f, p, sizeof f);  // STL is little-endian, as every machine we build for
  return f;
}

void ReadBinary(const std::string& bytes, uint32_t count, Scene& scene) {
  scene.faces.reserve(count);
  scene.positions.reserve(3 * size_t{count});
  for (uint32_t k = 0; k < count; ++k) {
    const char* facet = bytes.data() + kBinaryHeaderBytes + size_t{k} * kBinaryFacetBytes;
    Vec3 v[3];
    for (int c = 0; c < 3; ++c) {
      const char* p = facet + 12 * (c + 1);  // after the 12-byte normal
      v[c] = Vec3{ReadFloat(p), ReadFloat(p + 4), ReadFloat(p + 8)};
    }
    AddTriangle(scene, v, 0);
  }
}

// Names every face "facet<N>", or by the lines of `groups`.
absl::Status NameSurfaces(const std::optional<std::string>& groups, const std::string& name,
                          Scene& scene) {
  std::map<std::string, uint32_t> index;
  if (!groups) {
    for (size_t f = 0; f < scene.faces.size(); ++f) {
      scene.faces[f].object = scene.faces[f].group =
          InternName(scene.objects, index, absl::StrCat("facet", f + 1));
    }
    scene.groups = scene.objects;
    return absl::OkStatus();
  }
  std::istringstream lines(*groups);
  std::string line;
  size_t f = 0;
  for (int number = 1; std::getline(lines, line); ++number) {
    const std::string group(absl::StripAsciiWhitespace(line));
    if (group.empty() || group[0] == '#') continue;
    if (f == scene.faces.size()) {
      return absl::InvalidArgumentError(absl::StrCat(name, ".groups:", number, ": more names than the ",
                                                     scene.faces.size(), " facets of ", name));
    }
    scene.faces[f].object = scene.faces[f].group = InternName(scene.objects, index, group);
    ++f;
  }
  if (f != scene.faces.size()) {
    return absl::InvalidArgumentError(absl::StrCat(name, ".groups: ", f, " names for the ",
                                                   scene.faces.size(), " facets of ", name));
  }
  scene.groups = scene.objects;
  return absl::OkStatus();
}

std::optional<uint32_t> BinaryFacetCount(const std::string& bytes) {
  if (bytes.size() < kBinaryHeaderBytes) return std::nullopt;
  uint32_t count;
  std::memcpy(&count, bytes.data() + 80, sizeof count);
  if (bytes.size() != kBinaryHeaderBytes + uint64_t{count} * kBinaryFacetBytes) return std::nullopt;
  return count;
}

absl::StatusOr<std::string> ReadWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat(path, ": cannot open"));
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace

absl::StatusOr<Scene> LoadStlBytes(const std::string& bytes, const std::string& name,
                                   const std::optional<std::string>& groups) {
  Scene scene;
  scene.source = name;
  scene.materials.emplace_back().name = "stl";
  if (const std::optional<uint32_t> count = BinaryFacetCount(bytes)) {
    ReadBinary(bytes, *count, scene);
  } else if (absl::StartsWithIgnoreCase(absl::StripLeadingAsciiWhitespace(bytes), "solid")) {
    if (absl::Status s = ReadAscii(bytes, name, scene); !s.ok()) return s;
  } else {
    return absl::InvalidArgumentError(absl::StrCat(
        name, ": not an STL file (binary STL is 84 + 50 x facet-count bytes; this is ",
        bytes.size(), " bytes and does not start with 'solid')"));
  }
  if (scene.faces.empty()) return absl::InvalidArgumentError(name + ": no facets");
  if (absl::Status s = NameSurfaces(groups, name, scene); !s.ok()) return s;
  return scene;
}

absl::StatusOr<Scene> LoadStlFile(const std::string& path) {
  absl::StatusOr<std::string> bytes = ReadWholeFile(path);
  if (!bytes.ok()) return bytes.status();
  std::optional<std::string> groups;
  if (std::ifstream(path + ".groups")) {
    absl::StatusOr<std::string> text = ReadWholeFile(path + ".groups");
    if (!text.ok()) return text.status();
    groups = *std::move(text);
  }
  return LoadStlBytes(*bytes, path, groups);
}

}  // namespace radflux
