#include "solver/scene/import_rules.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "solver/scene/coplanar_overlaps.h"
#include "solver/scene/duplicate_faces.h"
#include "solver/scene/emitters.h"
#include "solver/scene/face_shape.h"
#include "solver/scene/polygon_triangulation.h"
#include "solver/scene/recentre.h"
#include "solver/scene/two_sided.h"
#include "solver/scene/validation.h"

namespace radflux {
namespace {

// Counts of one kind of fix-up, logged once at the end.
struct Tally {
  uint64_t count = 0;
  std::string first;

  void Add(const std::string& where) {
    if (count++ == 0) first = where;
  }
  void Log(ImportLog& log, const std::string& kind, const std::string& message) const {
    if (count > 0) log.Add(kind, message, first, count);
  }
};

absl::Status FixMaterials(const ImportOptions& options, Scene& scene) {
  if (absl::Status s = ApplyEmitOptions(options.emit, scene); !s.ok()) return s;
  std::vector<bool> used(scene.materials.size(), false);
  for (const Face& face : scene.faces) {
    if (face.material < used.size()) used[face.material] = true;
  }
  Tally clamped;
  for (size_t k = 0; k < scene.materials.size(); ++k) {
    Material& m = scene.materials[k];
    m.two_sided = m.two_sided || options.two_sided;
    if (!used[k]) continue;  // an unused material changes nothing
    bool at_or_above_one = false;
    for (int b = 0; b < kBands; ++b) at_or_above_one = at_or_above_one || m.reflectance[b] >= 1;
    if (!at_or_above_one) continue;
    if (options.strict) return ValidateMaterial(scene, m);
    for (int b = 0; b < kBands; ++b) m.reflectance[b] = std::min(m.reflectance[b], options.max_reflectance);
    clamped.Add(absl::StrCat("material '", m.name, "'"));
  }
  clamped.Log(scene.import_log, "reflectance_clamped",
              absl::StrFormat("{material|materials} with reflectance >= 1 clamped to %g", options.max_reflectance));
  return absl::OkStatus();
}

bool HasRepeats(const Scene& scene, const Face& face) {
  const size_t n = face.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    if (scene.positions[face.vertices[k]] == scene.positions[face.vertices[(k + 1) % n]]) return true;
  }
  return false;
}

// `face.vertices` without a vertex at the same position as the one before it (cyclically).
std::vector<uint32_t> WithoutRepeats(const Scene& scene, const Face& face) {
  std::vector<uint32_t> kept;
  for (size_t k = 0; k < face.vertices.size(); ++k) {
    const Vec3& p = scene.positions[face.vertices[k]];
    if (!kept.empty() && scene.positions[kept.back()] == p) continue;
    kept.push_back(face.vertices[k]);
  }
  while (kept.size() > 1 && scene.positions[kept.back()] == scene.positions[kept.front()]) kept.pop_back();
  return kept;
}

struct FaceTallies {
  Tally repeated, zero_area, non_planar, non_convex;
};

// Appends to `out` what face f becomes: itself, its triangles, or nothing. `polygon` is
// scratch space.
absl::Status FixFace(const ImportOptions& options, Scene& scene, size_t f, FaceTallies& tally,
                     std::vector<Vec3>& polygon, std::vector<Face>& out) {
  Face face = std::move(scene.faces[f]);
  if (face.vertices.size() >= 3 && !options.strict && HasRepeats(scene, face)) {
    tally.repeated.Add(scene.FaceLocation(f));
    face.vertices = WithoutRepeats(scene, face);
  }
  FacePolygonInto(scene, face, polygon);
  FaceShape shape;
  shape.degenerate = true;  // fewer than 3 distinct vertices
  if (face.vertices.size() >= 3) shape = MeasureFace(polygon);
  if (!shape.finite || (options.strict && (shape.degenerate || !shape.planar || !shape.convex))) {
    scene.faces[f] = std::move(face);  // as it was, for the message
    return ValidateFace(scene, f);
  }
  if (shape.degenerate) {
    tally.zero_area.Add(scene.FaceLocation(f));
    return absl::OkStatus();
  }
  if (shape.planar && shape.convex) {
    out.push_back(std::move(face));
    return absl::OkStatus();
  }
  (shape.planar ? tally.non_convex : tally.non_planar).Add(scene.FaceLocation(f));
  const std::vector<TriangleCorners> triangles =
      !shape.planar && polygon.size() == 4 ? SplitQuad(polygon) : TriangulatePolygon(polygon, shape.normal);
  for (const TriangleCorners& t : triangles) {
    Face triangle = face;
    triangle.vertices = {face.vertices[t[0]], face.vertices[t[1]], face.vertices[t[2]]};
    if (!MeasureFace(FacePolygon(scene, triangle)).degenerate) out.push_back(std::move(triangle));
  }
  return absl::OkStatus();
}

absl::Status FixFaces(const ImportOptions& options, Scene& scene) {
  FaceTallies tally;
  std::vector<Face> faces;
  faces.reserve(scene.faces.size());
  std::vector<Vec3> polygon;
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    if (absl::Status s = FixFace(options, scene, f, tally, polygon, faces); !s.ok()) return s;
  }
  scene.faces = std::move(faces);
  tally.repeated.Log(scene.import_log, "repeated_vertices_removed",
                     "{face|faces} with a repeated vertex simplified");
  tally.zero_area.Log(scene.import_log, "zero_area_dropped", "zero-area {face|faces} dropped");
  tally.non_planar.Log(scene.import_log, "non_planar_split", "non-planar {face|faces} split into triangles");
  tally.non_convex.Log(scene.import_log, "non_convex_triangulated",
                       "non-convex {face|faces} triangulated");
  return absl::OkStatus();
}

absl::Status DropDuplicates(const ImportOptions& options, Scene& scene) {
  const std::vector<uint32_t> duplicates = FindDuplicateFaces(scene);
  if (duplicates.empty()) return absl::OkStatus();
  if (options.strict) {
    return absl::InvalidArgumentError(absl::StrCat(scene.DescribeFace(duplicates[0]),
                                                   ": duplicate face (an earlier face has the "
                                                   "same vertices)"));
  }
  scene.import_log.Add("duplicate_dropped", "duplicate {face|faces} dropped",
                       scene.FaceLocation(duplicates[0]), duplicates.size());
  std::vector<Face> kept;
  kept.reserve(scene.faces.size() - duplicates.size());
  for (size_t f = 0, d = 0; f < scene.faces.size(); ++f) {
    if (d < duplicates.size() && duplicates[d] == f) {
      ++d;
      continue;
    }
    kept.push_back(std::move(scene.faces[f]));
  }
  scene.faces = std::move(kept);
  return absl::OkStatus();
}

void ReportOverlaps(Scene& scene) {
  const std::vector<FaceOverlap> overlaps = FindCoplanarOverlaps(scene);
  if (overlaps.empty()) return;
  scene.import_log.Add("coplanar_overlap",
                       "{pair|pairs} of coplanar faces {overlaps|overlap} (each hides the other; not changed)",
                       absl::StrCat(scene.FaceLocation(overlaps[0].a), " and ",
                                    scene.FaceLocation(overlaps[0].b)),
                       overlaps.size());
}

}  // namespace

absl::Status ApplyImportRules(const ImportOptions& options, Scene& scene) {
  if (!(options.max_reflectance > 0 && options.max_reflectance < 1)) {
    return absl::InvalidArgumentError("--max-reflectance must be in (0, 1)");
  }
  if (absl::Status s = FixMaterials(options, scene); !s.ok()) return s;
  RecentreScene(scene);
  if (!(scene.origin == Vec3{})) {
    scene.import_log.Add("recentred",
                         absl::StrFormat("scene recentred by (%.17g, %.17g, %.17g) for "
                                         "single-precision ray tracing; outputs keep the file's "
                                         "coordinates",
                                         scene.origin.x, scene.origin.y, scene.origin.z),
                         "", 1);
  }
  if (absl::Status s = FixFaces(options, scene); !s.ok()) return s;
  if (absl::Status s = DropDuplicates(options, scene); !s.ok()) return s;
  if (const uint64_t twins = AddBackFaces(scene); twins > 0) {
    scene.import_log.Add("two_sided", "two-sided {face|faces} given a back-face twin (each side lit on its own)", "",
                         twins);
  }
  ReportOverlaps(scene);
  return absl::OkStatus();
}

}  // namespace radflux
