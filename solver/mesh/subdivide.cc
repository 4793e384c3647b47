#include "solver/mesh/subdivide.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "absl/strings/str_cat.h"
#include "solver/mesh/contact_clip.h"
#include "solver/mesh/contact_footprints.h"

namespace radflux {
namespace {

// Steps along one side saturate here: far past the 2^31 patches SubdivideScene refuses, and
// small enough that a face's count (fan x steps^2) stays an int64. A length / h past int
// (--max-edge 1e-300) was cast to INT_MIN and meshed as one step: no refusal at all.
constexpr double kMaxSteps = 1 << 24;

int Steps(double length, double h) {
  if (h <= 0) return 1;
  return std::max(1, static_cast<int>(std::min(kMaxSteps, std::ceil(length / h - 1e-9))));
}

// The lengths that decide how finely a face is split (measured once per face, so choosing
// the edge length is cheap arithmetic however many times it is tried).
struct FaceExtent {
  double u = 0, v = 0;  // quad: the longer of each pair of opposite edges; else u = v =
                        // the longest edge (and centroid distance, for a fan)
  double longest_edge = 0;
  int fan = 1;       // patches per step^2: 1 for a triangle or quad, k for a k-gon fan
  double reach = 0;  // the farthest vertex from the first (bounds the bisection)
  bool quad = false;
  bool emitter = false;
  const QuadCuts* cuts = nullptr;  // lines it must be cut along (quads only), or null
};

FaceExtent MeasureExtent(const std::vector<Vec3>& p, bool emitter) {
  FaceExtent e;
  e.emitter = emitter;
  for (const Vec3& q : p) e.reach = std::max(e.reach, Length(q - p[0]));
  for (size_t i = 0; i < p.size(); ++i)
    e.longest_edge = std::max(e.longest_edge, Length(p[(i + 1) % p.size()] - p[i]));
  if (p.size() == 4) {
    e.quad = true;
    e.u = std::max(Length(p[1] - p[0]), Length(p[2] - p[3]));
    e.v = std::max(Length(p[3] - p[0]), Length(p[2] - p[1]));
    return e;
  }
  double longest = e.longest_edge;
  if (p.size() > 4) {
    Vec3 c;
    for (const Vec3& q : p) c += q / static_cast<double>(p.size());
    for (const Vec3& q : p) longest = std::max(longest, Length(q - c));
    e.fan = static_cast<int>(p.size());
  }
  e.u = e.v = longest;
  return e;
}

// Emitters are meshed no finer than kMaxEmitterSteps along an edge: their radiosity is
// almost all their own uniform E, so finer patches buy nothing, and every emitter patch
// costs an analytic column in every monte_carlo row.
double FaceEdgeLength(const FaceExtent& e, double h) {
  if (!e.emitter || h <= 0) return h;
  return std::max(h, e.longest_edge / kMaxEmitterSteps);
}

// Calls visit(a, b, n) for each interval [a, b] of a side of `length` between the `cuts`
// (parameters in (0, 1), ascending; null: none) with the n equal steps of at most `edge` it
// takes.
template <typename Visit>
void ForEachInterval(double length, double edge, const std::vector<double>* cuts, Visit visit) {
  double a = 0;
  if (cuts != nullptr) {
    for (double b : *cuts) {
      visit(a, b, Steps((b - a) * length, edge));
      a = b;
    }
  }
  visit(a, 1.0, Steps((1 - a) * length, edge));
}

int SideSteps(double length, double edge, const std::vector<double>* cuts) {
  int total = 0;
  ForEachInterval(length, edge, cuts, [&](double, double, int n) { total += n; });
  return total;
}

// The parameters of a side's grid lines, 0 and 1 included: its intervals' equal steps.
std::vector<double> SideLines(double length, double edge, const std::vector<double>* cuts) {
  std::vector<double> lines{0.0};
  ForEachInterval(length, edge, cuts, [&](double a, double b, int n) {
    for (int i = 1; i <= n; ++i) lines.push_back(a + (b - a) * (static_cast<double>(i) / n));
  });
  return lines;
}

// Subdivision counts of one face at edge length h: (nu, nv) for a quad, (n, n) otherwise.
std::pair<int, int> FaceSteps(const FaceExtent& e, double h) {
  const double edge = FaceEdgeLength(e, h);
  if (e.cuts == nullptr) return {Steps(e.u, edge), Steps(e.v, edge)};
  return {SideSteps(e.u, edge, &e.cuts->u), SideSteps(e.v, edge, &e.cuts->v)};
}

int64_t FacePatchCount(const FaceExtent& e, double h) {
  const auto [nu, nv] = FaceSteps(e, h);
  return int64_t{e.fan} * nu * nv;
}

// Builds one face's vertices and patches into the mesh.
class FaceMesher {
 public:
  FaceMesher(PatchMesh& mesh, uint32_t face, const Vec3& normal, const Material& material)
      : mesh_(mesh),
        face_(face),
        normal_(normal),
        two_sided_(material.two_sided),
        opacity_(static_cast<float>(material.opacity)) {}

  // The grid of quad p through the lines at parameters us (u: 0 -> 1) and vs (v: 0 -> 3),
  // each ascending from 0 to 1.
  void Quad(const std::vector<Vec3>& p, const std::vector<double>& us,
            const std::vector<double>& vs) {
    const uint32_t base = static_cast<uint32_t>(mesh_.positions.size());
    const int nu = static_cast<int>(us.size()) - 1, nv = static_cast<int>(vs.size()) - 1;
    for (double v : vs) {
      for (double u : us) {
        mesh_.positions.push_back(p[0] * ((1 - u) * (1 - v)) + p[1] * (u * (1 - v)) +
                                  p[2] * (u * v) + p[3] * ((1 - u) * v));
      }
    }
    auto id = [&](int i, int j) { return base + static_cast<uint32_t>(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j) {
      for (int i = 0; i < nu; ++i) Emit({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }

  // Triangle fan (a single triangle when p has 3 vertices), each subdivided n x n.
  void Fan(const std::vector<Vec3>& p, int n) {
    if (p.size() == 3 && n == 1) {  // the common case, without the key map: the same
      const uint32_t base = static_cast<uint32_t>(mesh_.positions.size());  // vertex order
      mesh_.positions.insert(mesh_.positions.end(), {p[2], p[0], p[1]});
      Emit({base + 1, base + 2, base, base});
      return;
    }
    if (p.size() == 3) {
      Triangle(p[0], p[1], p[2], n, [&](int a, int b) { return Key(0, a, b); });
      return;
    }
    Vec3 c;
    for (const Vec3& q : p) c += q / static_cast<double>(p.size());
    const int k = static_cast<int>(p.size());
    for (int s = 0; s < k; ++s) {
      const int next = (s + 1) % k;
      // Points on spokes are keyed by (spoke, step) so that neighbouring fan triangles share them.
      Triangle(c, p[s], p[next], n, [&](int a, int b) {
        if (a == 0 && b == 0) return Key(-1, 0, 0);
        if (b == 0) return Key(-2, s, a);
        if (a == 0) return Key(-2, next, b);
        return Key(s, a, b);
      });
    }
  }

 private:
  using Key = std::tuple<int, int, int>;

  template <typename KeyOf>
  void Triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, int n, KeyOf key_of) {
    auto id = [&](int a, int b) {
      auto [it, inserted] = ids_.try_emplace(key_of(a, b), 0u);
      if (inserted) {
        it->second = static_cast<uint32_t>(mesh_.positions.size());
        mesh_.positions.push_back(p0 + (p1 - p0) * (double(a) / n) + (p2 - p0) * (double(b) / n));
      }
      return it->second;
    };
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a + b < n; ++a) {
        const uint32_t up2 = id(a, b + 1);
        Emit({id(a, b), id(a + 1, b), up2, up2});
        if (a + b < n - 1) {
          const uint32_t down2 = id(a, b + 1);
          Emit({id(a + 1, b), id(a + 1, b + 1), down2, down2});
        }
      }
    }
  }

  void Emit(std::array<uint32_t, 4> v) {
    Patch patch;
    patch.v = v;
    patch.face = face_;
    patch.two_sided = two_sided_;
    patch.opacity = opacity_;
    FinishPatch(mesh_.positions, normal_, patch);
    mesh_.patches.push_back(patch);
  }

  PatchMesh& mesh_;
  uint32_t face_;
  Vec3 normal_;
  bool two_sided_;
  float opacity_;
  std::map<Key, uint32_t> ids_;
};

// The h in [lo, hi] (log-scale bisection, `iterations` steps) whose count(h) is closest to
// target; count must fall as h grows.
// count(lo) and count(hi) are only counted again when no step moved them (count can be
// costly: ContactAwareEdgeLength meshes the cut faces for it).
template <typename Count>
double BisectEdgeLength(Count&& count, int64_t target, double lo, double hi, int iterations) {
  std::optional<int64_t> above, below;  // count(lo), count(hi) when known
  for (int it = 0; it < iterations; ++it) {
    const double mid = std::sqrt(lo * hi);
    const int64_t at = count(mid);
    if (at > target) {
      lo = mid, above = at;
    } else {
      hi = mid, below = at;
    }
  }
  if (!above) above = count(lo);
  if (!below) below = count(hi);
  return (*above - target < target - *below) ? lo : hi;
}

double ChooseEdgeLength(const std::vector<FaceExtent>& extents, const MeshOptions& options) {
  if (options.max_edge > 0) return options.max_edge;
  if (options.target_patches <= 0) return 0;
  double longest = 0;
  for (const FaceExtent& e : extents) longest = std::max(longest, e.reach);
  auto count = [&](double h) {
    int64_t total = 0;
    for (const FaceExtent& e : extents) total += FacePatchCount(e, h);
    return total;
  };
  // Bisect (log scale) for the boundary where count(h) falls to <= target; pick the closer side.
  const double hi = longest * 2;
  const int64_t fewest = count(hi);  // every face one patch (or one fan)
  if (fewest >= options.target_patches) return hi;
  return BisectEdgeLength(count, options.target_patches, longest * 1e-7, hi, 100);
}

// Meshes face f at edge length h into `mesh` (its patches and positions appended), before
// any cut along its contacts; returns the face's unit normal.
Vec3 MeshFaceGrid(const Scene& scene, uint32_t f, const std::vector<Vec3>& polygon,
                  const FaceExtent& extent, double h, PatchMesh& mesh) {
  const Vec3 normal = Normalize(PolygonNewellNormal(polygon));
  FaceMesher mesher(mesh, f, normal, scene.materials[scene.faces[f].material]);
  const double edge = FaceEdgeLength(extent, h);
  if (polygon.size() == 4) {
    const QuadCuts* cuts = extent.cuts;
    mesher.Quad(polygon, SideLines(extent.u, edge, cuts ? &cuts->u : nullptr),
                SideLines(extent.v, edge, cuts ? &cuts->v : nullptr));
  } else {
    mesher.Fan(polygon, FaceSteps(extent, h).first);
  }
  return normal;
}

// A side of a solid resting on a face (a block's side on the floor) is lit less and less towards
// the concave corner at its foot, fastest within about a patch of it (the floor it sees there is
// the strip its own solid shadows); its first row of patches is cut this fraction of its
// patch edge from the foot, so that the row's flat B does not spread that falloff over a
// whole patch: the Cornell box's short block read 0.48% dark against Cycles with rows of
// 55 mm, its picture ringing from -15% to +40% above its foot; 0.04% with the strip.
constexpr double kFootStrip = 1.0 / 3;

// Adds to `cuts` the foot strips of the quads whose contacts name feet (FaceContacts::feet),
// at edge length h, and points their extents at them. A face not taller than three strips (a
// row) keeps its rows; emitters keep theirs (their B is almost all their own E).
void AddFootCuts(const Scene& scene, const std::vector<FaceContacts>& contacts, double h,
                 std::vector<FaceExtent>& extents, QuadCutsByFace& cuts) {
  if (!(h > 0)) return;  // one patch a face (MeshOptions with neither count nor edge)
  std::vector<Vec3> polygon;
  for (uint32_t f = 0; f < extents.size(); ++f) {
    if (!extents[f].quad || extents[f].emitter || contacts[f].feet.empty()) continue;
    FacePolygonInto(scene, scene.faces[f], polygon);
    const double strip = kFootStrip * FaceEdgeLength(extents[f], h);
    QuadCuts added = cuts.count(f) > 0 ? cuts.at(f) : QuadCuts{};
    for (int edge : contacts[f].feet) {
      // Edges 0 and 2 run along u (at v = 0 and 1), edges 1 and 3 along v (at u = 1 and 0).
      const bool along_u = edge % 2 == 0;
      const double across = Length(along_u ? polygon[3] - polygon[0] : polygon[1] - polygon[0]);
      const double t = strip / across;
      if (!(t > 0 && t < kFootStrip)) continue;
      std::vector<double>& lines = along_u ? added.v : added.u;
      const double at = edge == 0 || edge == 3 ? t : 1 - t;
      const auto next = std::lower_bound(lines.begin(), lines.end(), at);
      if ((next != lines.end() && *next - at < 1e-9) ||
          (next != lines.begin() && at - *(next - 1) < 1e-9)) {
        continue;
      }
      lines.insert(next, at);
    }
    if (added.u.empty() && added.v.empty()) continue;
    cuts[f] = std::move(added);
    extents[f].cuts = &cuts.at(f);
  }
}

// Meshes face f at edge length h into `mesh` (its patches and positions appended), cut
// along its contacts.
void MeshFace(const Scene& scene, uint32_t f, const std::vector<Vec3>& polygon,
              const FaceExtent& extent, double h, const FaceContacts& contacts, PatchMesh& mesh) {
  const uint32_t first_patch = static_cast<uint32_t>(mesh.patches.size());
  const uint32_t first_vertex = static_cast<uint32_t>(mesh.positions.size());
  const Vec3 normal = MeshFaceGrid(scene, f, polygon, extent, h, mesh);
  if (!contacts.empty()) {
    ClipFacePatches(contacts, normal, FaceEdgeLength(extent, h), first_patch, first_vertex, mesh);
  }
}

// With a target count, contact meshing adds patches beside contacts and takes them from
// under solids: h is re-chosen (between h and 4h, 8 steps: each meshes the cut faces) from the
// counts of the faces as meshed.
double ContactAwareEdgeLength(const Scene& scene, const std::vector<FaceExtent>& extents,
                              const std::vector<FaceContacts>& contacts, const MeshOptions& options,
                              double h) {
  if (options.max_edge > 0 || options.target_patches <= 0) return h;
  std::vector<uint32_t> touched;
  for (uint32_t f = 0; f < contacts.size(); ++f) {
    if (!contacts[f].empty()) touched.push_back(f);
  }
  if (touched.empty()) return h;
  std::vector<Vec3> polygon;
  auto count = [&](double edge) {
    int64_t total = 0;
    for (const FaceExtent& e : extents) total += FacePatchCount(e, edge);
    for (uint32_t f : touched) {
      PatchMesh face_mesh;
      FacePolygonInto(scene, scene.faces[f], polygon);
      const Vec3 normal = MeshFaceGrid(scene, f, polygon, extents[f], edge, face_mesh);
      const size_t cut =
          ClippedPatchCount(contacts[f], normal, FaceEdgeLength(extents[f], edge), 0, 0, face_mesh);
      total += static_cast<int64_t>(cut) - FacePatchCount(extents[f], edge);
    }
    return total;
  };
  if (count(h) <= options.target_patches) return h;
  return BisectEdgeLength(count, options.target_patches, h, 4 * h, 8);
}

}  // namespace

double TotalFaceArea(const Scene& scene) {
  double total = 0;
  std::vector<Vec3> polygon;
  for (const Face& face : scene.faces) {
    FacePolygonInto(scene, face, polygon);
    total += Length(PolygonNewellNormal(polygon)) / 2;
  }
  return total;
}

absl::StatusOr<PatchMesh> SubdivideScene(const Scene& scene, const MeshOptions& options,
                                         const QuadCutsByFace& given_cuts) {
  if (options.target_patches < 0 || options.max_edge < 0 || !std::isfinite(options.max_edge)) {
    return absl::InvalidArgumentError("patch count and max edge length must be >= 0");
  }
  std::vector<FaceExtent> extents;
  extents.reserve(scene.faces.size());
  std::vector<Vec3> polygon;
  for (const Face& face : scene.faces) {
    FacePolygonInto(scene, face, polygon);
    extents.push_back(MeasureExtent(polygon, scene.materials[face.material].IsEmitter()));
  }
  QuadCutsByFace cuts = given_cuts;  // and the foot strips below; its nodes do not move
  for (const auto& [f, face_cuts] : cuts) {
    if (f >= scene.faces.size()) {
      return absl::InvalidArgumentError(
          absl::StrCat("cuts for face ", f, " of a scene of ", scene.faces.size(), " faces"));
    }
    for (const std::vector<double>* side : {&face_cuts.u, &face_cuts.v}) {
      for (size_t k = 0; k < side->size(); ++k) {
        const double t = (*side)[k];
        if (!(t > 0 && t < 1) || (k > 0 && !(t > (*side)[k - 1]))) {
          return absl::InvalidArgumentError(absl::StrCat(
              scene.DescribeFace(f), ": cut lines must ascend within (0, 1), got ", t));
        }
      }
    }
    if (extents[f].quad) extents[f].cuts = &face_cuts;
  }
  // With at least as many faces as the target, every face is one patch; the contacts of the
  // faces of a patch's share of the area or more are still followed (a ceiling 2 cm above a
  // lamp keeps its slot: adaptive meshing starts from this mesh).
  const bool one_a_face = options.max_edge == 0 && options.target_patches > 0 &&
                          static_cast<int64_t>(scene.faces.size()) >= options.target_patches;
  const double min_contact_area =
      one_a_face ? std::max(options.min_contact_area,
                            TotalFaceArea(scene) / static_cast<double>(options.target_patches))
                 : options.min_contact_area;
  const std::vector<FaceContacts> contacts = options.follow_contacts
                                                 ? FindContacts(scene, min_contact_area)
                                                 : std::vector<FaceContacts>(scene.faces.size());
  const double h =
      ContactAwareEdgeLength(scene, extents, contacts, options, ChooseEdgeLength(extents, options));
  AddFootCuts(scene, contacts, h, extents, cuts);
  PatchMesh mesh;
  mesh.face_first_patch.reserve(scene.faces.size() + 1);
  mesh.face_first_vertex.reserve(scene.faces.size() + 1);
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    mesh.face_first_patch.push_back(static_cast<uint32_t>(mesh.patches.size()));
    mesh.face_first_vertex.push_back(static_cast<uint32_t>(mesh.positions.size()));
    const auto [nu, nv] = FaceSteps(extents[f], h);
    if (int64_t{nu} * nv > (int64_t{1} << 31)) {
      return absl::ResourceExhaustedError(
          absl::StrCat(scene.DescribeFace(f), ": subdivision would exceed 2^31 patches"));
    }
    FacePolygonInto(scene, scene.faces[f], polygon);
    MeshFace(scene, f, polygon, extents[f], h, contacts[f], mesh);
  }
  mesh.face_first_patch.push_back(static_cast<uint32_t>(mesh.patches.size()));
  mesh.face_first_vertex.push_back(static_cast<uint32_t>(mesh.positions.size()));
  return mesh;
}

MeshStats ComputeMeshStats(const PatchMesh& mesh) {
  MeshStats stats;
  stats.patches = mesh.size();
  if (mesh.patches.empty()) return stats;
  stats.min_area = stats.max_area = mesh.patches[0].area;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    double longest = 0;
    for (int k = 0; k < patch.VertexCount(); ++k) {
      longest = std::max(longest,
                         Length(mesh.Vertex(p, (k + 1) % patch.VertexCount()) - mesh.Vertex(p, k)));
    }
    const double shape = patch.IsTriangle() ? std::sqrt(3.0) / 4 : 1.0;
    stats.min_area = std::min(stats.min_area, patch.area);
    stats.max_area = std::max(stats.max_area, patch.area);
    stats.max_aspect = std::max(stats.max_aspect, longest * longest * shape / patch.area);
  }
  return stats;
}

}  // namespace radflux
