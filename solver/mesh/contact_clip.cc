#include "solver/mesh/contact_clip.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <tuple>
#include <utility>

#include "solver/mesh/footprint_polygons.h"
#include "solver/scene/polygon_triangulation.h"

namespace radflux {
namespace {

using Polygon = std::vector<Vec3>;

// Patches within `reach` of a footprint are split in four, and the pieces within reach / 2
// in four again: patches a quarter of the size hug the contact. (On the Cornell box at its
// defaults one level left the band in front of the short block at 12.3-13.2% of the floor's
// mean over three seeds, two levels 10.8-11.4%, Cycles 10.1%.)
constexpr int kSplitLevels = 2;

struct HalfPlane {
  Vec3 a;       // a point on its line
  Vec3 inward;  // in the face's plane, pointing inside
};

// A convex piece of a footprint: inside all its sides; lo/hi bound it.
struct ConvexPart {
  std::vector<HalfPlane> sides;
  Vec3 lo, hi;
  // A contact line's: the slab between its segment's ends. It cuts only pieces that reach
  // into the slab, so a cut runs on past the segment's end only within a piece it crosses.
  std::vector<HalfPlane> span;
};

ConvexPart MakePart(const Polygon& p, const Vec3& normal) {
  ConvexPart part{{}, p[0], p[0], {}};
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3& b = p[(i + 1) % p.size()];
    const Vec3 left = Cross(normal, b - p[i]);
    if (Length(left) > 0) part.sides.push_back({p[i], Normalize(left)});
    part.lo = {std::min(part.lo.x, p[i].x), std::min(part.lo.y, p[i].y),
               std::min(part.lo.z, p[i].z)};
    part.hi = {std::max(part.hi.x, p[i].x), std::max(part.hi.y, p[i].y),
               std::max(part.hi.z, p[i].z)};
  }
  return part;
}

// The footprints as convex polygons: a convex footprint whole, another one as its triangles.
std::vector<Polygon> ConvexPolygons(const std::vector<Footprint>& footprints, const Vec3& normal) {
  std::vector<Polygon> polygons;
  for (const Footprint& f : footprints) {
    if (IsConvexPolygon(f, normal)) {
      polygons.push_back(f);
      continue;
    }
    for (const TriangleCorners& t : TriangulatePolygon(f, normal)) {
      polygons.push_back({f[t[0]], f[t[1]], f[t[2]]});
    }
  }
  return polygons;
}

// The rectangle around segment a-b grown by `width` on every side, counter-clockwise about
// `normal`.
Polygon AroundSegment(const Vec3& a, const Vec3& b, const Vec3& normal, double width) {
  const Vec3 along = Normalize(b - a) * width, across = Cross(normal, along);
  return {a - along - across, b + along - across, b + along + across, a - along + across};
}

// Convex `p` grown by `width` on every side (mitred corners).
Polygon Inflated(const Polygon& p, const Vec3& normal, double width) {
  auto outward = [&](size_t i) { return Normalize(Cross(p[(i + 1) % p.size()] - p[i], normal)); };
  Polygon out;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3 before = outward((i + p.size() - 1) % p.size()), after = outward(i);
    out.push_back(p[i] + (before + after) * (width / (1 + Dot(before, after))));
  }
  return out;
}

double Area(const Polygon& p, const Vec3& normal) {
  return p.size() < 3 ? 0 : Dot(PolygonNewellNormal(p), normal) / 2;
}

bool Disjoint(const Polygon& p, const ConvexPart& part, double eps) {
  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& q : p) {
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
  }
  return lo.x > part.hi.x + eps || lo.y > part.hi.y + eps || lo.z > part.hi.z + eps ||
         hi.x < part.lo.x - eps || hi.y < part.lo.y - eps || hi.z < part.lo.z - eps;
}

// Where segment p-q crosses a line at signed distances sp, sq, computed from the
// lexicographically smaller end, so that the two patches sharing the edge get the same point.
Vec3 Crossing(const Vec3& p, const Vec3& q, double sp, double sq) {
  if (std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z)) return p + (q - p) * (sp / (sp - sq));
  return q + (p - q) * (sq / (sq - sp));
}

// The part of convex `poly` on side `sign` of `h` (+1 inside, -1 outside); points within
// eps of the line belong to both sides.
Polygon ClipSide(const Polygon& poly, const HalfPlane& h, double sign, double eps) {
  Polygon out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3& p = poly[i];
    const Vec3& q = poly[(i + 1) % poly.size()];
    const double sp = sign * Dot(p - h.a, h.inward), sq = sign * Dot(q - h.a, h.inward);
    if (sp >= -eps) out.push_back(p);
    if ((sp > eps && sq < -eps) || (sp < -eps && sq > eps)) out.push_back(Crossing(p, q, sp, sq));
  }
  return out;
}

// Whether all of `p` lies outside `h` (beyond eps).
bool AllOutside(const Polygon& p, const HalfPlane& h, double eps) {
  return std::none_of(p.begin(), p.end(),
                      [&](const Vec3& q) { return Dot(q - h.a, h.inward) > -eps; });
}

// Where convex `p` lies against `h`: all of it inside beyond eps (ClipSide keeps all of it
// on the inside and nothing outside), all outside beyond eps (the reverse), or either.
enum class SideOfLine { kInside, kOutside, kBoth };
SideOfLine SideOf(const Polygon& p, const HalfPlane& h, double eps) {
  bool inside = true, outside = true;
  for (const Vec3& q : p) {
    const double s = Dot(q - h.a, h.inward);
    inside = inside && s > eps;
    outside = outside && s < -eps;
  }
  return inside ? SideOfLine::kInside : outside ? SideOfLine::kOutside : SideOfLine::kBoth;
}

// Splits convex `piece` by `part`: its convex pieces outside `part` go to `outside`, the
// piece inside to `inside` when given (else it is left out).
void Split(Polygon piece, const ConvexPart& part, const Vec3& normal, double eps, double min_area,
           std::vector<Polygon>& outside, std::vector<Polygon>* inside) {
  if (Disjoint(piece, part, eps) ||
      std::any_of(part.span.begin(), part.span.end(),
                  [&](const HalfPlane& h) { return AllOutside(piece, h, eps); })) {
    outside.push_back(std::move(piece));
    return;
  }
  Polygon remaining = std::move(piece);
  for (const HalfPlane& h : part.sides) {
    // A side that does not cross the piece leaves it whole on one side, as ClipSide would,
    // without clipping (most pieces near a foot lie clear of most of its sides and lines).
    const SideOfLine side = SideOf(remaining, h, eps);
    if (side == SideOfLine::kInside) continue;
    if (side == SideOfLine::kOutside) {
      if (Area(remaining, normal) > min_area) outside.push_back(std::move(remaining));
      return;
    }
    Polygon out = ClipSide(remaining, h, -1, eps);
    if (Area(out, normal) > min_area) outside.push_back(std::move(out));
    remaining = ClipSide(remaining, h, 1, eps);
    if (Area(remaining, normal) <= min_area) return;
  }
  if (inside != nullptr) inside->push_back(std::move(remaining));
}

// Whether convex `p` may overlap `part`: no side of `part` has all of `p` outside it.
bool MayOverlap(const Polygon& p, const ConvexPart& part, double eps) {
  if (Disjoint(p, part, eps)) return false;
  return std::none_of(part.sides.begin(), part.sides.end(),
                      [&](const HalfPlane& h) { return AllOutside(p, h, eps); });
}

// `p` (a triangle or a quad) split into 4 by its edges' midpoints (and its centre for a quad).
// A midpoint is (a + b) * 0.5 whichever way the edge runs, so neighbours share it exactly.
void SplitInFour(const Polygon& p, std::vector<Polygon>& out) {
  const size_t n = p.size();
  std::vector<Vec3> mid(n);
  for (size_t i = 0; i < n; ++i) mid[i] = (p[i] + p[(i + 1) % n]) * 0.5;
  if (n == 3) {
    out.push_back({p[0], mid[0], mid[2]});
    out.push_back({mid[0], p[1], mid[1]});
    out.push_back({mid[2], mid[1], p[2]});
    out.push_back({mid[0], mid[1], mid[2]});
    return;
  }
  const Vec3 centre = (p[0] + p[1] + p[2] + p[3]) * 0.25;
  for (size_t i = 0; i < 4; ++i) out.push_back({p[i], mid[i], centre, mid[(i + 3) % 4]});
}

// `piece` without repeated points and corners within eps of the line through their
// neighbours.
Polygon Simplified(const Polygon& piece, const Vec3& normal, double eps) {
  Polygon p = piece;
  for (size_t i = 0; i < p.size() && p.size() > 3;) {
    const Vec3& prev = p[(i + p.size() - 1) % p.size()];
    const Vec3& next = p[(i + 1) % p.size()];
    const double twice_area = std::abs(Dot(Cross(p[i] - prev, next - p[i]), normal));
    if (twice_area <= eps * Length(next - prev)) {
      p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
      i = 0;
    } else {
      ++i;
    }
  }
  return p;
}

// The patches PieceEmitter makes of a piece of `corners` corners: one for a triangle or an
// uncut quad, else a fan of corners - 2 triangles.
size_t PiecePatches(size_t corners, bool cut) { return corners == 4 && !cut ? 1 : corners - 2; }

// Adds the face's patches for the pieces, sharing equal points.
class PieceEmitter {
 public:
  PieceEmitter(PatchMesh& mesh, const Vec3& normal) : mesh_(mesh), normal_(normal) {}

  // A triangle or quad as one patch; a cut piece of more than three corners as a fan of
  // triangles (a cut quad is rarely a parallelogram, and only a triangle's or a
  // parallelogram's midpoint split, which refinement uses, gives four equal quarters):
  // PiecePatches(piece.size(), cut) patches.
  // Its patches are hidden (Patch::hidden) when `hidden`.
  void Emit(const Polygon& piece, bool cut, bool hidden, const Patch& source) {
    std::vector<uint32_t> ids;
    for (const Vec3& p : piece) ids.push_back(Id(p));
    if (PiecePatches(ids.size(), cut) == 1 && ids.size() == 4) {
      Add({ids[0], ids[1], ids[2], ids[3]}, hidden, source);
      return;
    }
    for (size_t i = 1; i + 1 < ids.size(); ++i)
      Add({ids[0], ids[i], ids[i + 1], ids[i + 1]}, hidden, source);
  }

 private:
  uint32_t Id(const Vec3& p) {
    auto [it, inserted] = ids_.try_emplace(std::make_tuple(p.x, p.y, p.z), 0u);
    if (inserted) {
      it->second = static_cast<uint32_t>(mesh_.positions.size());
      mesh_.positions.push_back(p);
    }
    return it->second;
  }

  void Add(std::array<uint32_t, 4> v, bool hidden, const Patch& source) {
    Patch patch;
    patch.v = v;
    patch.face = source.face;
    patch.two_sided = source.two_sided;
    patch.opacity = source.opacity;
    patch.hidden = hidden;
    FinishPatch(mesh_.positions, normal_, patch);
    mesh_.patches.push_back(patch);
  }

  PatchMesh& mesh_;
  Vec3 normal_;
  std::map<std::tuple<double, double, double>, uint32_t> ids_;
};

// What a face's patches are cut by, in its plane.
struct Cuts {
  std::vector<ConvexPart> feet;   // left out
  std::vector<ConvexPart> slots;  // kept, the pieces inside hidden
  std::vector<ConvexPart> lines;  // each side of a foot as a line, both sides kept, for
                                  // patches near the foot (its box grown by the reach); each
                                  // contact line, for patches over its bounding box
  // Per level k: the feet grown by reach / 2^k; pieces there are split in four again.
  std::vector<std::vector<ConvexPart>> near;
  double eps = 0;  // points this close to a line are on it
};

// Adds grown(reach / 2^k), a convex polygon, to cuts.near[k] for each level k.
template <typename Grown>
void AddNear(Grown grown, const Vec3& normal, double reach, Cuts& cuts) {
  cuts.near.resize(kSplitLevels);
  for (int k = 0; k < kSplitLevels; ++k) {
    cuts.near[k].push_back(MakePart(grown(reach / (1 << k)), normal));
  }
}

// Adds the contact lines to `cuts`: each a cut along its line for the patches over its
// bounding box, refined beside it when it is at least 3 patches long.
void AddLines(const std::vector<ContactSegment>& lines, const Vec3& normal, double reach,
              Cuts& cuts, double& size) {
  for (const ContactSegment& line : lines) {
    const double length = Length(line.b - line.a);
    if (length == 0) continue;
    const Vec3& a = line.a;
    const Vec3& b = line.b;
    const Vec3 along = (b - a) / length;
    cuts.lines.push_back({{{a, Normalize(Cross(normal, along))}},
                          {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)},
                          {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)},
                          {{a, along}, {b, -along}}});
    if (reach > 0 && length >= 3 * reach) {
      AddNear([&](double width) { return AroundSegment(a, b, normal, width); }, normal, reach,
              cuts);
    }
    size = std::max(size, length);
  }
}

Cuts MakeCuts(const FaceContacts& contacts, const Vec3& normal, double reach) {
  Cuts cuts;
  double size = 0;
  for (const Polygon& p : ConvexPolygons(contacts.footprints, normal)) {
    const ConvexPart& foot = cuts.feet.emplace_back(MakePart(p, normal));
    const Vec3 grow = Vec3{1, 1, 1} * reach;
    // Refining spends patches: only where the foot is at least 3 patches across.
    if (reach > 0 && Length(PolygonNewellNormal(p)) / 2 >= 9 * reach * reach) {
      for (const HalfPlane& h : foot.sides) {
        cuts.lines.push_back({{h}, foot.lo - grow, foot.hi + grow, {}});
      }
      AddNear([&](double width) { return Inflated(p, normal, width); }, normal, reach, cuts);
    }
    size = std::max(size, Length(foot.hi - foot.lo));
  }
  AddLines(contacts.lines, normal, reach, cuts, size);
  for (const Polygon& p : ConvexPolygons(contacts.slots, normal)) {
    const ConvexPart& slot = cuts.slots.emplace_back(MakePart(p, normal));
    size = std::max(size, Length(slot.hi - slot.lo));
  }
  cuts.eps = 1e-9 * size;
  return cuts;
}

// The pieces of one patch (corners `corners`) outside the feet, each with whether a cut
// shaped it (else it is the patch or a quarter of it, as it was) and whether it lies in a slot.
struct Piece {
  Polygon corners;
  bool cut = false;
  bool hidden = false;
};

// `corners` split in four where it is near a foot, and the pieces split again (kSplitLevels).
std::vector<Polygon> Quartered(const Polygon& corners, const Cuts& cuts) {
  std::vector<Polygon> pieces{corners}, next;
  for (const std::vector<ConvexPart>& level : cuts.near) {
    next.clear();
    for (const Polygon& piece : pieces) {
      if (std::any_of(level.begin(), level.end(),
                      [&](const ConvexPart& part) { return MayOverlap(piece, part, cuts.eps); })) {
        SplitInFour(piece, next);
      } else {
        next.push_back(piece);
      }
    }
    pieces.swap(next);
  }
  return pieces;
}

std::vector<Piece> PatchPieces(const Polygon& corners, double area, const Cuts& cuts,
                               const Vec3& normal) {
  const std::vector<Polygon> whole = Quartered(corners, cuts);
  std::vector<Polygon> pieces = whole, next;
  const double min_area = 1e-9 * area;
  auto split_all = [&](const ConvexPart& part, bool keep_inside) {
    next.clear();
    for (Polygon& piece : pieces) {
      Split(std::move(piece), part, normal, cuts.eps, min_area, next,
            keep_inside ? &next : nullptr);
    }
    pieces.swap(next);
  };
  for (const ConvexPart& part : cuts.feet) split_all(part, false);
  for (const ConvexPart& line : cuts.lines) split_all(line, true);
  std::vector<Polygon> hidden;  // pieces inside a slot, split no further
  for (const ConvexPart& slot : cuts.slots) {
    next.clear();
    for (Polygon& piece : pieces) {
      Split(std::move(piece), slot, normal, cuts.eps, min_area, next, &hidden);
    }
    pieces.swap(next);
  }
  std::vector<Piece> out;
  for (bool in_slot : {false, true}) {
    for (Polygon& piece : in_slot ? hidden : pieces) {
      const bool cut = std::find(whole.begin(), whole.end(), piece) == whole.end();
      out.push_back({cut ? Simplified(piece, normal, cuts.eps) : std::move(piece), cut, in_slot});
    }
  }
  return out;
}

// Calls piece_of(patch, piece) for every piece of the patches [first_patch, end) of `mesh`
// (positions from first_vertex) that `cuts` leave.
template <typename PieceOf>
void ForEachPiece(const Cuts& cuts, const Vec3& normal, std::span<const Patch> patches,
                  std::span<const Vec3> positions, uint32_t first_vertex, PieceOf&& piece_of) {
  Polygon corners;
  for (const Patch& patch : patches) {
    corners.clear();
    for (int k = 0; k < patch.VertexCount(); ++k)
      corners.push_back(positions[patch.v[k] - first_vertex]);
    for (const Piece& piece : PatchPieces(corners, patch.area, cuts, normal)) {
      piece_of(patch, piece);
    }
  }
}

}  // namespace

void ClipFacePatches(const FaceContacts& contacts, const Vec3& normal, double reach,
                     uint32_t first_patch, uint32_t first_vertex, PatchMesh& mesh) {
  const Cuts cuts = MakeCuts(contacts, normal, reach);
  if (cuts.feet.empty() && cuts.lines.empty() && cuts.slots.empty()) return;
  const std::vector<Patch> patches(mesh.patches.begin() + first_patch, mesh.patches.end());
  const std::vector<Vec3> positions(mesh.positions.begin() + first_vertex, mesh.positions.end());
  mesh.patches.resize(first_patch);
  mesh.positions.resize(first_vertex);
  PieceEmitter emitter(mesh, normal);
  ForEachPiece(cuts, normal, patches, positions, first_vertex,
               [&](const Patch& patch, const Piece& piece) {
                 emitter.Emit(piece.corners, piece.cut, piece.hidden, patch);
               });
}

size_t ClippedPatchCount(const FaceContacts& contacts, const Vec3& normal, double reach,
                         uint32_t first_patch, uint32_t first_vertex, const PatchMesh& mesh) {
  const Cuts cuts = MakeCuts(contacts, normal, reach);
  const size_t unclipped = mesh.patches.size() - first_patch;
  if (cuts.feet.empty() && cuts.lines.empty() && cuts.slots.empty()) return unclipped;
  size_t count = 0;
  ForEachPiece(cuts, normal, std::span(mesh.patches).subspan(first_patch),
               std::span(mesh.positions).subspan(first_vertex), first_vertex,
               [&](const Patch&, const Piece& piece) {
                 count += PiecePatches(piece.corners.size(), piece.cut);
               });
  return count;
}

}  // namespace radflux
