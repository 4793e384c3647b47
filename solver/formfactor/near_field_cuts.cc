#include "solver/formfactor/near_field_cuts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "solver/core/inverse_bilinear.h"
#include "solver/core/parallel.h"
#include "solver/formfactor/polygon_form_factor.h"
#include "solver/formfactor/surface_pair_integrator.h"
#include "solver/mesh/subdivide.h"
#include "solver/raytrace/embree_ray_caster.h"

namespace radflux {
namespace {

constexpr int kIntervals = 32;  // samples along a line: kIntervals + 1
constexpr std::array<double, 3> kLines = {1.0 / 6, 0.5, 5.0 / 6};
using Line = std::array<double, kIntervals + 1>;

// The distance between the boxes [alo, ahi] and [blo, bhi] (0 when they overlap).
double Gap(const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi) {
  return Length(Vec3{std::max({0.0, alo.x - bhi.x, blo.x - ahi.x}),
                     std::max({0.0, alo.y - bhi.y, blo.y - ahi.y}),
                     std::max({0.0, alo.z - bhi.z, blo.z - ahi.z})});
}

struct Emitter {
  SurfaceShape shape;   // its normal the side it emits from
  double emission = 0;  // E, mean over bands
};

// A blocker must lie this far (as a share of the segment) from both ends of the segment
// from a point to an emitter: the face itself and the emitter (and its back-face twin) are none.
constexpr double kSegmentMargin = 1e-4;

// Whether some vertex of `polygon` lies strictly in front of the plane through `origin`.
bool AnyInFront(const std::vector<Vec3>& polygon, const Vec3& origin, const Vec3& normal) {
  return std::any_of(polygon.begin(), polygon.end(),
                     [&](const Vec3& p) { return Dot(p - origin, normal) > 0; });
}

// The n equal steps along `line`, each showing its mean, that best trade their miss (the mean
// absolute deviation from the values, as a share of their mean) against their number, at
// `step_cost` a step: a peak across a housing's width takes steps, the falloff over the last
// few cm of a long tube (which only a fine grid along all of it would resolve) does not.
int StepsFor(const Line& line, double step_cost) {
  double mean = 0;
  for (double g : line) mean += g / line.size();
  if (!(mean > 0)) return 1;  // no light along this line
  int best = 1;
  double best_cost = INFINITY;
  for (int n = 1; n <= kMaxNearFieldSteps; ++n) {
    double deviation = 0;
    for (int k = 0; k < n; ++k) {
      const int first = (k * kIntervals + n - 1) / n, last = ((k + 1) * kIntervals) / n;
      double step_mean = 0;
      for (int i = first; i <= last; ++i) step_mean += line[i] / (last - first + 1);
      for (int i = first; i <= last; ++i) deviation += std::abs(line[i] - step_mean);
    }
    const double cost = deviation / (mean * line.size()) + step_cost * n;
    if (cost < best_cost) best = n, best_cost = cost;
  }
  return best;
}

// The scene's emitting faces sorted by their boxes' lowest x, and their power (mean over bands).
std::vector<Emitter> SortedEmitters(const Scene& scene, double* power) {
  std::vector<Emitter> emitters;
  std::vector<Vec3> polygon;
  for (const Face& face : scene.faces) {
    if (!scene.materials[face.material].IsEmitter()) continue;
    FacePolygonInto(scene, face, polygon);
    Emitter e{MakeSurfaceShape(polygon), MeanComponent(scene.materials[face.material].emission)};
    *power += e.emission * e.shape.area;
    emitters.push_back(std::move(e));
  }
  std::sort(emitters.begin(), emitters.end(),
            [](const Emitter& a, const Emitter& b) { return a.shape.lo.x < b.shape.lo.x; });
  return emitters;
}

// One side's lines: the n equal steps' or, where the light along the side is flat enough for
// one step (n = 1), the outlines' (ascending; those outside (kOutlineMargin, 1 -
// kOutlineMargin) dropped, and all of them when there are more than kMaxNearFieldSteps).
// Equal steps follow a peaked light already; one step spans the falloff past an emitter's
// ends, which only a line there separates from the light over it.
std::vector<double> SideCuts(int n, std::vector<double> outlines) {
  std::vector<double> lines;
  if (n > 1) {
    for (int i = 1; i < n; ++i) lines.push_back(static_cast<double>(i) / n);
    return lines;
  }
  std::erase_if(outlines, [](double t) { return !(t > kOutlineMargin && t < 1 - kOutlineMargin); });
  if (outlines.size() > static_cast<size_t>(kMaxNearFieldSteps)) return lines;
  lines = std::move(outlines);
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

// The cuts of scene face f by the rule of the header (none: nullopt), among `emitters`
// (sorted by their boxes' lowest x, none wider in x than `widest`; `power` their emitted
// power); each emitter's light at a point counts only when `caster` (on the scene's faces, or
// null: no blocker) finds nothing between the point and the emitter's centroid (a ceiling 2 cm
// above a housing sees nothing of the tube inside).
std::optional<QuadCuts> CutsOfFace(const Scene& scene, size_t f,
                                   const std::vector<Emitter>& emitters, double widest,
                                   double power, const RayCaster* caster) {
  const Face& face = scene.faces[f];
  if (face.vertices.size() != 4 || scene.materials[face.material].IsEmitter()) return std::nullopt;
  std::vector<Vec3> polygon;
  FacePolygonInto(scene, face, polygon);
  const SurfaceShape quad = MakeSurfaceShape(polygon);
  const std::vector<Vec3>& p = quad.polygon;
  double reach = 0;
  for (int k = 0; k < 4; ++k) reach = std::max(reach, Length(p[(k + 1) % 4] - p[k]));
  std::vector<const Emitter*> near;
  auto e = std::lower_bound(emitters.begin(), emitters.end(), quad.lo.x - reach - widest,
                            [](const Emitter& em, double x) { return em.shape.lo.x < x; });
  for (; e != emitters.end() && e->shape.lo.x <= quad.hi.x + reach; ++e) {
    const SurfaceShape& em = e->shape;
    if (Gap(quad.lo, quad.hi, em.lo, em.hi) <= reach && AnyInFront(em.polygon, p[0], quad.normal) &&
        AnyInFront(p, em.polygon[0], em.normal)) {
      near.push_back(&*e);
    }
  }
  if (near.empty()) return std::nullopt;
  std::vector<uint8_t> lights(near.size(), 0);  // whether near[i] lit some sample point
  double irradiance_sum = 0;
  auto form_factor = [&](double u, double v) {
    const Vec3 x =
        p[0] * ((1 - u) * (1 - v)) + p[1] * (u * (1 - v)) + p[2] * (u * v) + p[3] * ((1 - u) * v);
    double sum = 0;  // F; irradiance_sum gathers F E
    for (size_t i = 0; i < near.size(); ++i) {
      const SurfaceShape& shape = near[i]->shape;
      if (Dot(x - shape.polygon[0], shape.normal) <= 0) continue;
      if (caster != nullptr &&
          caster->Occluded({x, shape.centroid - x, kSegmentMargin, 1 - kSegmentMargin})) {
        continue;
      }
      const double factor = PointToPolygonFormFactor(x, quad.normal, shape.polygon);
      sum += factor;
      irradiance_sum += factor * near[i]->emission;
      lights[i] = lights[i] || factor > 0;
    }
    return sum;
  };
  std::array<Line, kLines.size()> along_u, along_v;
  double peak = 0;
  for (size_t l = 0; l < kLines.size(); ++l) {
    for (int i = 0; i <= kIntervals; ++i) {
      const double t = static_cast<double>(i) / kIntervals;
      along_u[l][i] = form_factor(t, kLines[l]);
      along_v[l][i] = form_factor(kLines[l], t);
      peak = std::max({peak, along_u[l][i], along_v[l][i]});
    }
  }
  const double reflected = MeanComponent(scene.materials[face.material].reflectance) *
                           irradiance_sum / (2 * kLines.size() * (kIntervals + 1)) * quad.area;
  if (peak < kNearFieldMinPeak || reflected < kNearFieldMinPower * power) return std::nullopt;
  int nu = 1, nv = 1;
  for (size_t l = 0; l < kLines.size(); ++l) {
    nu = std::max(nu, StepsFor(along_u[l], kNearFieldStepCost));
    nv = std::max(nv, StepsFor(along_v[l], kNearFieldStepCost));
  }
  std::vector<double> outline_u, outline_v;  // each lighting emitter's extent over the face
  for (size_t i = 0; i < near.size() && (nu == 1 || nv == 1); ++i) {  // used only there
    if (!lights[i]) continue;
    double u_lo = INFINITY, u_hi = -INFINITY, v_lo = INFINITY, v_hi = -INFINITY;
    for (const Vec3& x : near[i]->shape.polygon) {
      const auto [u, v] = InverseBilinear({p[0], p[1], p[2], p[3]}, quad.normal, x);
      u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u);
      v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
    }
    outline_u.insert(outline_u.end(), {u_lo, u_hi});
    outline_v.insert(outline_v.end(), {v_lo, v_hi});
  }
  QuadCuts cuts{SideCuts(nu, std::move(outline_u)), SideCuts(nv, std::move(outline_v))};
  if (cuts.u.empty() && cuts.v.empty()) return std::nullopt;
  return cuts;
}

}  // namespace

absl::StatusOr<QuadCutsByFace> NearFieldCuts(const Scene& scene) {
  QuadCutsByFace cuts;
  double power = 0;
  const std::vector<Emitter> emitters = SortedEmitters(scene, &power);
  if (emitters.empty()) return cuts;
  double widest = 0;
  for (const Emitter& e : emitters) widest = std::max(widest, e.shape.hi.x - e.shape.lo.x);
  // First without blockers: the faces that could need cuts at all (cheap; most scenes few).
  std::vector<uint8_t> candidate(scene.faces.size(), 0);
  ParallelFor(static_cast<int64_t>(scene.faces.size()), 256, 0, [&](int64_t begin, int64_t end) {
    for (int64_t f = begin; f < end; ++f) {
      candidate[static_cast<size_t>(f)] =
          CutsOfFace(scene, static_cast<size_t>(f), emitters, widest, power, nullptr).has_value();
    }
  });
  std::vector<uint32_t> faces;
  for (uint32_t f = 0; f < candidate.size(); ++f) {
    if (candidate[f]) faces.push_back(f);
  }
  if (faces.empty()) return cuts;
  // Then again with the scene's faces as blockers, one patch a face.
  MeshOptions whole;
  whole.max_edge = std::numeric_limits<double>::max();
  whole.follow_contacts = false;
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, whole);
  if (!mesh.ok()) return mesh.status();
  absl::StatusOr<std::unique_ptr<EmbreeRayCaster>> caster = EmbreeRayCaster::Create(*mesh);
  if (!caster.ok()) return caster.status();
  std::vector<std::optional<QuadCuts>> found(faces.size());
  ParallelFor(static_cast<int64_t>(faces.size()), 16, 0, [&](int64_t begin, int64_t end) {
    for (int64_t k = begin; k < end; ++k) {
      found[static_cast<size_t>(k)] =
          CutsOfFace(scene, faces[static_cast<size_t>(k)], emitters, widest, power, caster->get());
    }
  });
  for (size_t k = 0; k < faces.size(); ++k) {
    if (found[k].has_value()) cuts.emplace(faces[k], *std::move(found[k]));
  }
  return cuts;
}

}  // namespace radflux
