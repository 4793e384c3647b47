#include "solver/mesh/contact_footprints.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>

#include "solver/mesh/footprint_polygons.h"

namespace radflux {
namespace {

struct Box {
  Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
          std::numeric_limits<double>::max()};
  Vec3 hi{-std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
          -std::numeric_limits<double>::max()};

  void Add(const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  Box Padded(double pad) const { return {lo - Vec3{pad, pad, pad}, hi + Vec3{pad, pad, pad}}; }
};

struct FaceGeometry {
  std::vector<Vec3> polygon;
  Vec3 normal;  // unit
  Box box;
  double area = 0;         // scene units^2
  double width = 0;        // twice the area over the longest edge (scene units)
  bool emits = false;      // its material is an emitter
  bool two_sided = false;  // its material is two-sided: a twin lies back to back with it
};

bool Overlap(const Box& a, const Box& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
         a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

// The bounding boxes of the faces `members` in a uniform grid of about one face per cell (at
// most 256 cells per axis); a face over more than kMaxCells cells is kept in a list of big
// faces instead, so that the grid holds O(members) entries whatever the faces' shapes.
class FaceGrid {
 public:
  FaceGrid(const std::vector<FaceGeometry>& faces, const Box& scene, std::vector<uint32_t> members)
      : faces_(faces), members_(std::move(members)), lo_(scene.lo), seen_(faces.size(), 0) {
    const Vec3 extent = scene.hi - scene.lo;
    n_ = std::clamp(static_cast<int64_t>(2 * std::cbrt(double(members_.size()))), int64_t{1},
                    int64_t{256});
    cell_ = std::max({extent.x, extent.y, extent.z, 1e-300}) / double(n_);
    for (uint32_t f : members_) {
      if (CellCount(faces[f].box) > kMaxCells) {
        big_.push_back(f);
      } else {
        ForCells(faces[f].box, [&](int64_t key) { cells_[key].push_back(f); });
      }
    }
  }

  // Calls visit(face) once for each member whose box overlaps `box` (one query at a time).
  template <typename Visit>
  void ForBox(const Box& box, Visit&& visit) {
    ++stamp_;
    auto once = [&](uint32_t f) {
      if (seen_[f] == stamp_ || !Overlap(faces_[f].box, box)) return;
      seen_[f] = stamp_;
      visit(f);
    };
    for (uint32_t f : big_) once(f);
    if (CellCount(box) > double(members_.size())) {  // cheaper to try every member
      for (uint32_t f : members_) once(f);
      return;
    }
    ForCells(box, [&](int64_t key) {
      const auto it = cells_.find(key);
      if (it == cells_.end()) return;
      for (uint32_t f : it->second) once(f);
    });
  }

 private:
  static constexpr double kMaxCells = 512;

  int64_t Index(double v, double lo) const {
    return std::clamp(static_cast<int64_t>(std::floor((v - lo) / cell_)), int64_t{0}, n_ - 1);
  }
  double CellCount(const Box& b) const {
    return double(Index(b.hi.x, lo_.x) - Index(b.lo.x, lo_.x) + 1) *
           double(Index(b.hi.y, lo_.y) - Index(b.lo.y, lo_.y) + 1) *
           double(Index(b.hi.z, lo_.z) - Index(b.lo.z, lo_.z) + 1);
  }
  template <typename Body>
  void ForCells(const Box& b, Body&& body) const {
    for (int64_t x = Index(b.lo.x, lo_.x); x <= Index(b.hi.x, lo_.x); ++x) {
      for (int64_t y = Index(b.lo.y, lo_.y); y <= Index(b.hi.y, lo_.y); ++y) {
        for (int64_t z = Index(b.lo.z, lo_.z); z <= Index(b.hi.z, lo_.z); ++z) {
          body((x * n_ + y) * n_ + z);
        }
      }
    }
  }

  const std::vector<FaceGeometry>& faces_;
  std::vector<uint32_t> members_;
  Vec3 lo_;
  int64_t n_ = 1;
  double cell_ = 1;
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;
  std::vector<uint32_t> big_;
  std::vector<uint32_t> seen_;  // per face: the last query that visited it
  uint32_t stamp_ = 0;
};

// An edge of a standing face in a receiver's plane, oriented so that the face's normal
// points to its right seen from the receiver's front (a solid's foot runs counter-clockwise).
struct ContactEdge {
  Vec3 a, b;
  uint32_t face = 0;
  int edge = 0;  // its index in the face's polygon (i -> i + 1)
};

double LongestEdge(const std::vector<Vec3>& polygon) {
  double longest = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    longest = std::max(longest, Length(polygon[(i + 1) % polygon.size()] - polygon[i]));
  }
  return longest;
}

double PlaneDistance(const FaceGeometry& receiver, const Vec3& p) {
  return Dot(p - receiver.polygon[0], receiver.normal);
}

// The edges of `stander` lying in `receiver`'s plane, when `stander` stands on its front.
// Whether segment a-b lies on the line of one of the receiver's edges (a face meeting the
// receiver along its border, e.g. its neighbour in a tessellated surface, is not standing
// on it).
bool AlongBorder(const FaceGeometry& receiver, const Vec3& a, const Vec3& b, double tol) {
  const std::vector<Vec3>& r = receiver.polygon;
  for (size_t i = 0; i < r.size(); ++i) {
    const Vec3 dir = Normalize(r[(i + 1) % r.size()] - r[i]);
    if (Length(Cross(a - r[i], dir)) <= tol && Length(Cross(b - r[i], dir)) <= tol) return true;
  }
  return false;
}

void AddContactEdges(const FaceGeometry& receiver, const FaceGeometry& stander, uint32_t face,
                     double tol, std::vector<ContactEdge>& out) {
  if (std::abs(Dot(receiver.normal, stander.normal)) > 1 - 1e-9) return;
  const std::vector<Vec3>& p = stander.polygon;
  for (const Vec3& q : p) {
    if (PlaneDistance(receiver, q) < -tol) return;
  }
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % p.size()];
    if (std::abs(PlaneDistance(receiver, a)) > tol || std::abs(PlaneDistance(receiver, b)) > tol ||
        AlongBorder(receiver, a, b, tol)) {
      continue;
    }
    const bool normal_left = Dot(Cross(receiver.normal, b - a), stander.normal) > 0;
    const int edge = static_cast<int>(i);
    out.push_back(normal_left ? ContactEdge{b, a, face, edge} : ContactEdge{a, b, face, edge});
  }
}

// The gap under a face lying against a receiver that still hides it: 2% of the face's size
// (the square root of its area). Light reaches into such a gap only through the slit around
// it, seen at an angle of about gap / depth, so only a band a few gaps wide along the edge
// gets any, weakly (at 2%, of the order of a tenth of the hidden area). The conference room's
// boards hang 3.6 units off the wall and are triangles of 255 units: 1.4%.
constexpr double kCoverGap = 0.02;

// The farthest in front of `receiver` a face may lie and still hide it (kHides) or make a
// slot of it (kSlot), scene units (contact_footprints.h). An emitter is hidden by the smaller
// face's size: its light leaves through the slit and lights the cover, which a hidden emitter
// loses (the corridor's lamp tops, 40 cm wide, 2 cm under the ceiling's outward twin, were
// hidden by the ceiling's size and the ceiling read -85%). Other faces by the cover's: a small
// face a few mm off a wall, hidden, has no patches deep in the gap that the room's rays
// rarely reach (office2's switch plate's back read +154% on one seed of four when kept).
double HidingGap(const FaceGeometry& receiver, const FaceGeometry& cover) {
  return kCoverGap * std::sqrt(receiver.emits ? std::min(receiver.area, cover.area) : cover.area);
}
double SlotGap(const FaceGeometry& receiver, const FaceGeometry& cover) {
  return std::min(cover.width, kCoverGap * std::sqrt(receiver.area));
}

// What a face lying in front of a receiver makes of the receiver's part under it.
enum class CoverKind { kNone, kHides, kSlot };

struct Cover {
  CoverKind kind = CoverKind::kNone;
  Footprint polygon;  // `cover`'s outline projected onto the receiver, ccw about its normal
};

// What `cover` makes of `receiver` (contact_footprints.h): with its back to it (facing the
// same way), every corner more than tol and at most HidingGap in front, it hides the part
// under it (a light hung just below a ceiling, a poster on a wall), or makes a slot of it
// when the receiver is two-sided and does not emit (left out, the part would be a hole: the
// ray casters see through its twin's back); emitting and facing it, every corner more than
// tol and at most SlotGap in front, it makes a slot of it.
Cover CoverOf(const FaceGeometry& receiver, const FaceGeometry& cover, double tol) {
  const double cos = Dot(receiver.normal, cover.normal);
  if (cos == 0 || (cos < 0 && !cover.emits)) return {};
  const double gap = cos < 0 ? SlotGap(receiver, cover) : HidingGap(receiver, cover);
  const bool keep = cos < 0 || (receiver.two_sided && !receiver.emits);
  Cover out{keep ? CoverKind::kSlot : CoverKind::kHides, {}};
  for (const Vec3& q : cover.polygon) {
    const double d = PlaneDistance(receiver, q);
    if (d <= tol || d > gap) return {};
    out.polygon.push_back(q - receiver.normal * d);
  }
  if (cos < 0) std::reverse(out.polygon.begin(), out.polygon.end());
  return out;
}

// Closed loops of `edges` (chained end to start within tol), as the loops' edges' indices.
std::vector<std::vector<size_t>> ChainLoops(const std::vector<ContactEdge>& edges, double tol) {
  std::vector<std::vector<size_t>> loops;
  std::vector<bool> used(edges.size(), false);
  for (size_t s = 0; s < edges.size(); ++s) {
    if (used[s]) continue;
    used[s] = true;
    std::vector<size_t> loop{s};
    while (Length(edges[loop.back()].b - edges[loop.front()].a) > tol) {
      const ContactEdge& last = edges[loop.back()];
      size_t next = edges.size();
      for (size_t e = 0; e < edges.size() && next == edges.size(); ++e) {
        // The next edge starts where this one ends and does not run straight back (a
        // two-sided solid's back-face twins give every edge its reverse).
        if (!used[e] && Length(edges[e].a - last.b) <= tol && Length(edges[e].b - last.a) > tol) {
          next = e;
        }
      }
      if (next == edges.size()) break;
      used[next] = true;
      loop.push_back(next);
    }
    if (loop.size() >= 3 && Length(edges[loop.back()].b - edges[loop.front()].a) <= tol) {
      loops.push_back(loop);
    }
  }
  return loops;
}

// Whether segment a-b is `s` either way round, within tol.
bool SameSegment(const ContactSegment& s, const Vec3& a, const Vec3& b, double tol) {
  return (Length(s.a - a) <= tol && Length(s.b - b) <= tol) ||
         (Length(s.a - b) <= tol && Length(s.b - a) <= tol);
}

// The contact edges of `edges` outside the footprints (`in_foot` per edge), each segment once
// and none that is a footprint's edge (`foot_edges`).
std::vector<ContactSegment> OpenLines(const std::vector<ContactEdge>& edges,
                                      const std::vector<bool>& in_foot,
                                      const std::vector<ContactSegment>& foot_edges, double tol) {
  std::vector<ContactSegment> lines;
  for (size_t e = 0; e < edges.size(); ++e) {
    auto same = [&](const ContactSegment& s) {
      return SameSegment(s, edges[e].a, edges[e].b, tol);
    };
    if (in_foot[e] || std::any_of(foot_edges.begin(), foot_edges.end(), same) ||
        std::any_of(lines.begin(), lines.end(), same)) {
      continue;
    }
    lines.push_back({edges[e].a, edges[e].b});
  }
  return lines;
}

// Whether a face of `object` facing away from `receiver` and above it covers `point`.
bool HasLid(const Scene& scene, const std::vector<FaceGeometry>& faces, FaceGrid& grid,
            const FaceGeometry& receiver, uint32_t object, const Vec3& point, double reach,
            double tol) {
  Box column;
  column.Add(point);
  column.Add(point + receiver.normal * reach);
  bool found = false;
  grid.ForBox(column.Padded(tol), [&](uint32_t g) {
    const FaceGeometry& lid = faces[g];
    if (found || scene.faces[g].object != object || Dot(lid.normal, receiver.normal) <= 0) return;
    for (const Vec3& q : lid.polygon) {
      if (PlaneDistance(receiver, q) <= tol) return;
    }
    bool positive = false, negative = false;
    for (size_t i = 0; i < lid.polygon.size(); ++i) {
      const Vec3& a = lid.polygon[i];
      const Vec3& b = lid.polygon[(i + 1) % lid.polygon.size()];
      const double side = Dot(Cross(b - a, point - a), receiver.normal);
      positive |= side > 0;
      negative |= side < 0;
    }
    found = !(positive && negative);
  });
  return found;
}

// The contacts of receiver r from its contact edges: the loops that are feet of solids (a
// lid above them; `lids` a grid of every face) become footprints, the rest lines.
// `feet` gets (face, edge) for each edge of a footprint's loop: a solid's side and its foot.
void AddFootprintsAndLines(const Scene& scene, const std::vector<FaceGeometry>& faces,
                           FaceGrid& lids, uint32_t r, const std::vector<ContactEdge>& edges,
                           double diagonal, double tol, FaceContacts& contacts,
                           std::vector<std::pair<uint32_t, int>>& feet) {
  std::vector<bool> in_foot(edges.size(), false);
  std::vector<ContactSegment> foot_edges;
  for (const std::vector<size_t>& loop : ChainLoops(edges, tol)) {
    const uint32_t object = scene.faces[edges[loop[0]].face].object;
    Footprint polygon;
    Vec3 centroid;
    bool one_object = true;
    for (size_t e : loop) {
      polygon.push_back(edges[e].a);
      centroid += edges[e].a / double(loop.size());
      one_object &= scene.faces[edges[e].face].object == object;
    }
    if (!one_object || Dot(PolygonNewellNormal(polygon), faces[r].normal) <= tol * tol ||
        !HasLid(scene, faces, lids, faces[r], object, centroid, diagonal, tol)) {
      continue;
    }
    for (size_t e : loop) {
      in_foot[e] = true;
      foot_edges.push_back({edges[e].a, edges[e].b});
      feet.emplace_back(edges[e].face, edges[e].edge);
    }
    contacts.footprints.push_back(std::move(polygon));
  }
  contacts.lines = OpenLines(edges, in_foot, foot_edges, tol);
}

}  // namespace

std::vector<FaceContacts> FindContacts(const Scene& scene, double min_receiver_area) {
  std::vector<FaceContacts> contacts(scene.faces.size());
  if (scene.faces.empty()) return contacts;
  std::vector<FaceGeometry> faces(scene.faces.size());
  std::vector<uint32_t> all(faces.size()), receivers;
  Box scene_box;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    faces[f].polygon = FacePolygon(scene, scene.faces[f]);
    faces[f].normal = Normalize(PolygonNewellNormal(faces[f].polygon));
    for (const Vec3& p : faces[f].polygon) faces[f].box.Add(p);
    scene_box.Add(faces[f].box.lo);
    scene_box.Add(faces[f].box.hi);
    faces[f].area = Length(PolygonNewellNormal(faces[f].polygon)) / 2;
    faces[f].width = 2 * faces[f].area / std::max(LongestEdge(faces[f].polygon), 1e-300);
    faces[f].emits = scene.materials[scene.faces[f].material].IsEmitter();
    faces[f].two_sided = scene.materials[scene.faces[f].material].two_sided;
    all[f] = f;
    if (faces[f].area >= min_receiver_area) receivers.push_back(f);
  }
  const double diagonal = Length(scene_box.hi - scene_box.lo);
  const double tol = 1e-5 * diagonal;
  FaceGrid receiver_grid(faces, scene_box, receivers);
  std::vector<std::vector<ContactEdge>> edges(faces.size());
  for (uint32_t s = 0; s < faces.size(); ++s) {
    const double reach =
        std::max({tol, kCoverGap * std::sqrt(faces[s].area), faces[s].emits ? faces[s].width : 0});
    receiver_grid.ForBox(faces[s].box.Padded(reach), [&](uint32_t r) {
      if (r == s) return;
      AddContactEdges(faces[r], faces[s], s, tol, edges[r]);
      Cover cover = CoverOf(faces[r], faces[s], tol);
      if (cover.kind == CoverKind::kHides) {
        contacts[r].footprints.push_back(std::move(cover.polygon));
      } else if (cover.kind == CoverKind::kSlot) {
        contacts[r].slots.push_back(std::move(cover.polygon));
      }
    });
  }
  FaceGrid lid_grid(faces, scene_box, std::move(all));
  std::vector<std::pair<uint32_t, int>> feet;
  for (uint32_t r : receivers) {
    AddFootprintsAndLines(scene, faces, lid_grid, r, edges[r], diagonal, tol, contacts[r], feet);
    contacts[r].slots = JoinedConvexPolygons(std::move(contacts[r].slots), faces[r].normal, tol);
  }
  for (const auto& [face, edge] : feet) contacts[face].feet.push_back(edge);
  for (FaceContacts& c : contacts) {
    std::sort(c.feet.begin(), c.feet.end());
    c.feet.erase(std::unique(c.feet.begin(), c.feet.end()), c.feet.end());
  }
  return contacts;
}

}  // namespace radflux
