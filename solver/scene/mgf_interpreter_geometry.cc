// MgfInterpreter: the statements that make geometry (v, p, n, f, fh and the primitives).
#include <algorithm>

#include "absl/strings/str_cat.h"
#include "solver/scene/mgf_interpreter.h"

namespace radflux {
namespace {

absl::Status Invalid(const std::string& what) { return absl::InvalidArgumentError(what); }

// The numbers in words[first..first+count); error naming the entity otherwise.
absl::Status ReadNumbers(const std::vector<std::string>& words, size_t first, size_t count,
                         double* out) {
  for (size_t i = 0; i < count; ++i) {
    if (first + i >= words.size() || !ParseMgfNumber(words[first + i], &out[i])) {
      return Invalid(absl::StrCat("'", words[0], "' argument ", first + i, " is not a number"));
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<MgfInterpreter::Vertex*> MgfInterpreter::FindVertex(const std::string& name) {
  auto it = vertices_.find(name);
  if (it == vertices_.end()) return Invalid(absl::StrCat("vertex '", name, "' is not defined"));
  return &it->second;
}

absl::Status MgfInterpreter::VertexStatement(const std::vector<std::string>& words) {
  const std::string& e = words[0];
  if (e == "p" || e == "n") {
    if (words.size() != 4) return Invalid(absl::StrCat("'", e, "' needs 3 numbers"));
    double v[3];
    if (absl::Status s = ReadNumbers(words, 1, 3, v); !s.ok()) return s;
    (e == "p" ? vertex_->p : vertex_->n) = {v[0], v[1], v[2]};
    vertex_->epoch = 0;
    return absl::OkStatus();
  }
  if (words.size() == 1) {
    unnamed_vertex_ = Vertex{};
    vertex_ = &unnamed_vertex_;
    return absl::OkStatus();
  }
  if (words.size() > 4 || (words.size() >= 3 && words[2] != "=")) {
    return Invalid("'v' is 'v name', 'v name =' or 'v name = template'");
  }
  if (words.size() == 2) {
    absl::StatusOr<Vertex*> v = FindVertex(words[1]);
    if (!v.ok()) return v.status();
    vertex_ = *v;
    return absl::OkStatus();
  }
  Vertex value;
  if (words.size() == 4) {
    absl::StatusOr<Vertex*> tmpl = FindVertex(words[3]);
    if (!tmpl.ok()) return tmpl.status();
    value = {(*tmpl)->p, (*tmpl)->n};
  }
  vertex_ = &vertices_[words[1]];
  *vertex_ = value;
  return absl::OkStatus();
}

uint32_t MgfInterpreter::ScenePoint(Vertex& v) {
  if (v.epoch != epoch_) {
    v.index = static_cast<uint32_t>(scene_.positions.size());
    v.epoch = epoch_;
    scene_.positions.push_back(Transform().Apply(v.p));
  }
  return v.index;
}

absl::Status MgfInterpreter::AddFace(std::vector<uint32_t> vertices, const FileRun& run, int line) {
  if (scene_.faces.size() >= limits_.max_faces) {
    return Invalid(absl::StrCat("more than ", limits_.max_faces, " faces (xf array too large?)"));
  }
  if (Transform().Mirrors()) std::reverse(vertices.begin(), vertices.end());
  radflux::Face face;
  face.vertices = std::move(vertices);
  face.material = materials_.Intern(scene_, absl::StrCat(run.path, ":", line));
  face.object = object_;
  face.source_line = line;
  face.source_file = run.file_index;
  scene_.faces.push_back(std::move(face));
  return absl::OkStatus();
}

absl::Status MgfInterpreter::Face(const FileRun& run, const MgfStatement& s) {
  if (s.words.size() < 4) return Invalid("'f' needs at least 3 vertices");
  std::vector<Vertex*> corners;
  for (size_t i = 1; i < s.words.size(); ++i) {
    absl::StatusOr<Vertex*> v = FindVertex(s.words[i]);
    if (!v.ok()) return v.status();
    corners.push_back(*v);
  }
  std::vector<uint32_t> indices;
  for (Vertex* v : corners) indices.push_back(ScenePoint(*v));
  return AddFace(std::move(indices), run, s.line);
}

absl::Status MgfInterpreter::FaceWithHoles(const FileRun& run, const MgfStatement& s) {
  constexpr size_t kMaxVertices = 512;  // bridging is cubic in the vertex count at worst
  if (s.words.size() > kMaxVertices) {
    return Invalid(absl::StrCat("'fh' with more than ", kMaxVertices, " vertices"));
  }
  std::vector<std::vector<Vertex*>> contours(1);
  for (size_t i = 1; i < s.words.size(); ++i) {
    if (s.words[i] == "-") {
      contours.emplace_back();
      continue;
    }
    absl::StatusOr<Vertex*> v = FindVertex(s.words[i]);
    if (!v.ok()) return v.status();
    contours.back().push_back(*v);
  }
  std::vector<Vertex*> all;
  std::vector<std::vector<Vec3>> points;
  for (const std::vector<Vertex*>& contour : contours) {
    if (contour.size() < 3) return Invalid("'fh' contours need at least 3 vertices each");
    points.emplace_back();
    for (Vertex* v : contour) {
      points.back().push_back(v->p);
      all.push_back(v);
    }
  }
  absl::StatusOr<std::vector<uint32_t>> order =
      BridgeHoles(points[0], {points.begin() + 1, points.end()});
  if (!order.ok()) return order.status();
  std::vector<uint32_t> indices;
  for (uint32_t k : *order) indices.push_back(ScenePoint(*all[k]));
  return AddFace(std::move(indices), run, s.line);
}

absl::StatusOr<MgfMesh> MgfInterpreter::PrimitiveMesh(const std::vector<std::string>& w) {
  const std::string& e = w[0];
  const int n = options_.curve_segments;
  if (e == "prism") {
    if (w.size() < 5) return Invalid("'prism' needs at least 3 vertices and a length");
    std::vector<Vec3> base;
    for (size_t i = 1; i + 1 < w.size(); ++i) {
      absl::StatusOr<Vertex*> v = FindVertex(w[i]);
      if (!v.ok()) return v.status();
      base.push_back((*v)->p);
    }
    double length = 0;
    if (absl::Status st = ReadNumbers(w, w.size() - 1, 1, &length); !st.ok()) return st;
    return ExtrudePrism(base, length);
  }
  // sph v r | cyl v1 r v2 | cone v1 r1 v2 r2 | ring v r_in r_out | torus v r_in r_out
  const size_t expected = e == "sph" ? 3 : (e == "cone" ? 5 : 4);
  if (w.size() != expected) {
    return Invalid(absl::StrCat("'", e, "' needs ", expected - 1, " arguments"));
  }
  const bool two_ends = e == "cyl" || e == "cone";
  absl::StatusOr<Vertex*> a = FindVertex(w[1]);
  if (!a.ok()) return a.status();
  absl::StatusOr<Vertex*> b = two_ends ? FindVertex(w[3]) : a;
  if (!b.ok()) return b.status();
  double r[2];
  if (absl::Status st = ReadNumbers(w, 2, 1, &r[0]); !st.ok()) return st;
  r[1] = r[0];
  if (e != "sph" && e != "cyl") {
    if (absl::Status st = ReadNumbers(w, e == "cone" ? 4 : 3, 1, &r[1]); !st.ok()) return st;
  }
  const Vertex& va = **a;
  if (e == "sph") return TessellateSphere(va.p, r[0], n);
  if (two_ends) return TessellateCone(va.p, r[0], (*b)->p, r[1], n);
  if (e == "ring") return TessellateRing(va.p, va.n, r[0], r[1], n);
  return TessellateTorus(va.p, va.n, r[0], r[1], n);
}

absl::Status MgfInterpreter::Primitive(const FileRun& run, const MgfStatement& s) {
  absl::StatusOr<MgfMesh> mesh = PrimitiveMesh(s.words);
  if (!mesh.ok()) return mesh.status();
  const uint32_t base = static_cast<uint32_t>(scene_.positions.size());
  for (const Vec3& point : mesh->points) scene_.positions.push_back(Transform().Apply(point));
  for (std::vector<uint32_t>& face : mesh->faces) {
    for (uint32_t& v : face) v += base;
    if (absl::Status st = AddFace(std::move(face), run, s.line); !st.ok()) return st;
  }
  return absl::OkStatus();
}

}  // namespace radflux
