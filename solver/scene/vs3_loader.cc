#include "solver/scene/vs3_loader.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"

namespace radflux {
namespace {

// One record: its words (View3D's separators: blank, tab, comma; '/' or '!' starts a
// comment) and where it is.
struct Record {
  std::vector<std::string> words;
  std::string rest;  // the text after the first word, comment removed, blanks trimmed
  std::string file;
  int line = 0;

  absl::Status Error(const std::string& what) const {
    return absl::InvalidArgumentError(absl::StrCat(file, ":", line, ": ", what));
  }
  absl::StatusOr<int> Int(size_t k, const char* what) const {
    int value;
    if (k >= words.size()) return Error(absl::StrCat("missing ", what));
    if (!absl::SimpleAtoi(words[k], &value)) {
      return Error(absl::StrCat("bad ", what, " '", words[k], "' (an integer)"));
    }
    return value;
  }
  absl::StatusOr<double> Real(size_t k, const char* what) const {
    double value;
    if (k >= words.size()) return Error(absl::StrCat("missing ", what));
    if (!absl::SimpleAtod(words[k], &value) || !std::isfinite(value)) {
      return Error(absl::StrCat("bad ", what, " '", words[k], "' (a finite number)"));
    }
    return value;
  }
};

Record SplitRecord(const std::string& line, const std::string& file, int number) {
  const std::string text = line.substr(0, line.find_first_of("/!"));
  Record record;
  record.file = file;
  record.line = number;
  for (absl::string_view w : absl::StrSplit(text, absl::ByAnyChar(" \t,\r"), absl::SkipEmpty())) {
    record.words.emplace_back(w);
  }
  if (!record.words.empty()) {
    const size_t first = text.find(record.words[0]) + record.words[0].size();
    record.rest = std::string(absl::StripAsciiWhitespace(text.substr(first)));
  }
  return record;
}

absl::Status ReadControl(const Record& r, Vs3Control& c) {
  std::vector<std::string> w = absl::StrSplit(r.rest, absl::ByAnyChar("= ,\t\r"), absl::SkipEmpty());
  for (size_t k = 0; k < w.size(); k += 2) {
    const std::string key = absl::AsciiStrToLower(w[k]);
    int value = 0;
    double real = 0;
    if (k + 1 >= w.size()) return r.Error(absl::StrCat("control word '", w[k], "' has no value"));
    const bool is_int = absl::SimpleAtoi(w[k + 1], &value);
    if (key == "eps") {
      if (!absl::SimpleAtod(w[k + 1], &real) || !(real > 0 && real < 1)) {
        return r.Error(absl::StrCat("bad eps value '", w[k + 1], "' (a number in (0, 1))"));
      }
      c.eps = real;
      continue;
    }
    if (!is_int) return r.Error(absl::StrCat("bad ", w[k], " value '", w[k + 1], "' (an integer)"));
    if (key == "encl") c.enclosure = value != 0;
    else if (key == "emit") c.emittances = value != 0;
    else if (key == "maxu") c.max_u = std::max(value, 4);  // View3D resets < 4 to 4
    else if (key == "maxo") c.max_o = std::max(value, 4);
    else if (key == "mino") c.min_o = std::max(value, 0);
    else if (key == "row") c.row = std::max(value, 0);
    else if (key == "col") c.col = std::max(value, 0);
    else if (key == "list") c.list = value;
    else if (key == "prjd") c.prj_reverse = value != 0;
    else if (key == "out") {
      if (value < 0 || value > 2) return r.Error(absl::StrCat("bad out value ", value, " (0, 1 or 2)"));
      c.out = value;
    } else {
      return r.Error(absl::StrCat("unknown control word '", w[k],
                                  "' (View3D's are eps, list, out, encl, emit, maxU, maxO, minO, "
                                  "row, col, prjD)"));
    }
  }
  if (c.col > 0 && c.row == 0) return r.Error("col needs row (as in View3D)");
  return absl::OkStatus();
}

// Builds the model record by record.
class Vs3Reader {
 public:
  explicit Vs3Reader(const std::string& name) {
    model_.scene.source = name;
  }

  // Reads one record; sets `ended` at E or *.
  absl::Status Read(const Record& r, bool& ended) {
    const char kind = absl::ascii_toupper(static_cast<unsigned char>(r.words[0][0]));
    switch (kind) {
      case 'T': model_.title = r.rest; return absl::OkStatus();
      case 'F':
        if (r.words.size() >= 2 && r.words[1] == "3") return absl::OkStatus();
        return r.Error("only geometry format 'F 3' (vertex/surface) is supported");
      case 'C': return ReadControl(r, model_.control);
      case 'V': return ReadVertex(r);
      case 'S': case 'O': return ReadSurface(r, kind == 'O');
      case 'M': case 'N':
        return r.Error("mask (M) and null (N) surfaces are not supported by radflux");
      case 'X': return absl::OkStatus();  // ignored by View3D's GetVS3D too
      case 'E': case '*': ended = true; return absl::OkStatus();
      default:
        return r.Error(absl::StrCat("unknown record '", r.words[0],
                                    "' (expected T, F, C, V, S, O, E, / or !)"));
    }
  }

  absl::StatusOr<Vs3Model> Finish() && {
    if (model_.scene.faces.empty()) {
      return absl::InvalidArgumentError(model_.scene.source + ": no surfaces (S records)");
    }
    model_.scene.groups = model_.scene.objects;
    return std::move(model_);
  }

 private:
  absl::Status ReadVertex(const Record& r) {
    absl::StatusOr<int> n = r.Int(1, "vertex number");
    if (!n.ok()) return n.status();
    if (*n != static_cast<int>(model_.scene.positions.size()) + 1) {
      return r.Error(absl::StrCat("vertex ", *n, " out of sequence (expected ",
                                  model_.scene.positions.size() + 1, ")"));
    }
    double xyz[3];
    for (int k = 0; k < 3; ++k) {
      absl::StatusOr<double> x = r.Real(2 + k, "vertex coordinate");
      if (!x.ok()) return x.status();
      xyz[k] = *x;
    }
    model_.scene.positions.push_back(Vec3{xyz[0], xyz[1], xyz[2]});
    return absl::OkStatus();
  }

  absl::StatusOr<std::vector<uint32_t>> ReadCorners(const Record& r) {
    std::vector<uint32_t> corners;
    const int count = static_cast<int>(model_.scene.positions.size());
    for (int k = 0; k < 4; ++k) {
      absl::StatusOr<int> v = r.Int(2 + k, "vertex number");
      if (!v.ok()) return v.status();
      if (k == 3 && *v == 0) break;  // a triangle
      if (*v < 1 || *v > count) {
        return r.Error(absl::StrCat("vertex ", *v, " is not defined (", count,
                                    " vertices so far; V records come before the surfaces)"));
      }
      corners.push_back(static_cast<uint32_t>(*v - 1));
    }
    return corners;
  }

  absl::Status ReadSurface(const Record& r, bool obstruction) {
    absl::StatusOr<int> n = r.Int(1, "surface number");
    if (!n.ok()) return n.status();
    Scene& scene = model_.scene;
    if (*n != static_cast<int>(scene.faces.size()) + 1) {
      return r.Error(absl::StrCat("surface ", *n, " out of sequence (expected ",
                                  scene.faces.size() + 1, ")"));
    }
    if (!obstruction && seen_obstruction_) {
      return r.Error("radiating surface after an obstruction surface (all S come before O)");
    }
    seen_obstruction_ = seen_obstruction_ || obstruction;
    absl::StatusOr<std::vector<uint32_t>> corners = ReadCorners(r);
    if (!corners.ok()) return corners.status();
    Face face;
    face.vertices = *std::move(corners);
    face.source_line = r.line;
    face.obstruction = obstruction;
    std::string name = absl::StrCat("obstruction#", *n);
    if (!obstruction) {
      absl::StatusOr<std::string> surface = ReadSurfaceData(r, *n, face);
      if (!surface.ok()) return surface.status();
      name = *surface;
    } else {
      face.material = MaterialFor(0.999);
    }
    face.object = face.group = InternName(scene.objects, objects_, name);
    scene.faces.push_back(std::move(face));
    return absl::OkStatus();
  }

  // base, cmbn, emit and name of an S record; returns the surface's unique name.
  absl::StatusOr<std::string> ReadSurfaceData(const Record& r, int n, Face& face) {
    absl::StatusOr<int> base = r.Int(6, "base surface number");
    if (!base.ok()) return base.status();
    absl::StatusOr<int> combine = r.Int(7, "combine surface number");
    if (!combine.ok()) return combine.status();
    if (*base != 0 || *combine != 0) {
      return r.Error("subsurfaces (base > 0) and combined surfaces (cmbn > 0) are not supported");
    }
    absl::StatusOr<double> emit = r.Real(8, "emittance");
    if (!emit.ok()) return emit.status();
    if (r.words.size() < 10) return r.Error("missing surface name");
    face.material = MaterialFor(std::clamp(*emit, 0.001, 0.999));
    const std::string& name = r.words[9];
    return objects_.count(name) ? absl::StrCat(name, "#", n) : name;
  }

  uint32_t MaterialFor(double emittance) {
    const std::string name = absl::StrFormat("emit=%.3f", emittance);
    auto [it, inserted] = materials_.try_emplace(name, model_.scene.materials.size());
    if (inserted) {
      const double rho = 1 - emittance;
      Material material;
      material.name = name;
      material.reflectance = {rho, rho, rho};
      model_.scene.materials.push_back(material);
    }
    return it->second;
  }

 private:
  Vs3Model model_;
  std::map<std::string, uint32_t> objects_, materials_;
  bool seen_obstruction_ = false;
};

}  // namespace

absl::StatusOr<Vs3Model> LoadVs3Text(const std::string& text, const std::string& name) {
  Vs3Reader reader(name);
  std::istringstream lines(text);
  std::string line;
  bool ended = false;
  for (int number = 1; !ended && std::getline(lines, line); ++number) {
    const Record record = SplitRecord(line, name, number);
    if (record.words.empty()) continue;  // blank or comment
    if (absl::Status s = reader.Read(record, ended); !s.ok()) return s;
  }
  return std::move(reader).Finish();
}

absl::StatusOr<Vs3Model> LoadVs3File(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat(path, ": cannot open"));
  std::ostringstream text;
  text << in.rdbuf();
  return LoadVs3Text(text.str(), path);
}

}  // namespace radflux
