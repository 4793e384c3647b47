#include "solver/formfactor/analytic_pair.h"

#include <cmath>

#include "solver/core/sampling.h"
#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

// Pattern streams, so the samples of different purposes are independent.
constexpr uint64_t kPointStream = 1;
constexpr uint64_t kTargetStream = 2;

std::vector<Vec3> PatchPolygon(const PatchMesh& mesh, uint32_t p) {
  std::vector<Vec3> polygon;
  for (int k = 0; k < mesh.patches[p].VertexCount(); ++k) polygon.push_back(mesh.Vertex(p, k));
  return polygon;
}

// cos(theta_x) cos(theta_y) / r^2 of the pair (x, y): the form-factor kernel up to pi,
// 0 when either point is behind the other's plane.
double PairKernel(const Vec3& x, const Vec3& nx, const Vec3& y, const Vec3& ny) {
  const Vec3 d = y - x;
  const double cx = Dot(nx, d), cy = -Dot(ny, d), r2 = Dot(d, d);
  return cx > 0 && cy > 0 ? cx * cy / (r2 * r2) : 0;
}

// A shadow ray between two surface points, each lifted off its surface by the epsilon.
bool Blocked(const RowContext& context, const Vec3& x, const Vec3& nx, const Vec3& y,
             const Vec3& ny) {
  const Vec3 origin = x + nx * context.ray_epsilon;
  const Vec3 target = y + ny * context.ray_epsilon;
  return context.caster->Occluded({origin, target - origin, 0, 1 - 1e-6});
}

bool AnyVertexInFront(const PatchMesh& mesh, uint32_t of, const Patch& plane) {
  const double scale = std::sqrt(plane.area);
  for (int k = 0; k < mesh.patches[of].VertexCount(); ++k) {
    if (Dot(mesh.Vertex(of, k) - plane.centroid, plane.normal) > 1e-9 * scale) return true;
  }
  return false;
}

}  // namespace

bool PatchesCanExchange(const PatchMesh& mesh, uint32_t i, uint32_t j) {
  return i != j && AnyVertexInFront(mesh, j, mesh.patches[i]) &&
         AnyVertexInFront(mesh, i, mesh.patches[j]);
}

std::vector<Vec3> PatchSamplePoints(const PatchMesh& mesh, uint32_t i, int s, uint64_t seed) {
  std::vector<Vec3> points;
  const uint32_t pattern = PatternSeed(seed, i, kPointStream);
  const PatchPointSampler sample_point(mesh, i);
  for (int m = 0; m < s; ++m) points.push_back(sample_point(MultiJitteredSample(m, s, pattern)));
  return points;
}

double AnalyticPairFormFactor(const RowContext& context, uint32_t i,
                              const std::vector<Vec3>& points, uint32_t j, uint64_t seed,
                              uint64_t& rays) {
  const PatchMesh& mesh = *context.mesh;
  const Patch& pi = mesh.patches[i];
  const Patch& pj = mesh.patches[j];
  // All points of i share i's plane, so clip j against it once.
  std::vector<Vec3> polygon = PatchPolygon(mesh, j);
  polygon = ClipPolygonToHalfSpace(polygon, pi.centroid, pi.normal);
  if (polygon.size() < 3) return 0;
  const uint32_t pattern = PatternSeed(seed ^ (uint64_t{i} << 32), j, kTargetStream);
  const int s = static_cast<int>(points.size());
  const PatchPointSampler sample_target(mesh, j);
  double unoccluded = 0, weight = 0, visible_weight = 0, f = 0;
  for (int m = 0; m < s; ++m) {
    // A point behind j's plane sees only j's back: no exchange from there (this matters
    // where i runs under a solid, e.g. floor patches partly beneath a block).
    if (Dot(points[m] - pj.centroid, pj.normal) <= 0) continue;
    // Repeated points (hemicube: s copies of the centroid) share one contour integral.
    if (m == 0 || !(points[m] == points[m - 1])) {
      f = UnclippedPointToPolygonFormFactor(points[m], pi.normal, polygon);
    }
    unoccluded += f;
    const Vec3 target = sample_target(MultiJitteredSample(m, s, pattern));
    const double kernel = PairKernel(points[m], pi.normal, target, pj.normal);
    if (kernel <= 0) continue;
    weight += kernel;
    ++rays;
    if (!Blocked(context, points[m], pi.normal, target, pj.normal)) visible_weight += kernel;
  }
  if (unoccluded <= 0) return 0;
  if (weight <= 0) {
    // Every sampled target lay behind i's plane: one ray to the visible part's centre.
    Vec3 centre;
    for (const Vec3& p : polygon) centre += p / static_cast<double>(polygon.size());
    ++rays;
    return Blocked(context, points[0], pi.normal, centre, pj.normal) ? 0 : unoccluded / s;
  }
  return unoccluded / s * (visible_weight / weight);
}

uint64_t AddAnalyticColumns(const RowContext& context, uint32_t i,
                            std::span<const uint32_t> columns, int samples, uint64_t seed,
                            RowAccumulator& row) {
  return AddAnalyticColumns(context, i, columns, PatchSamplePoints(*context.mesh, i, samples, seed),
                            seed, row);
}

uint64_t AddAnalyticColumns(const RowContext& context, uint32_t i,
                            std::span<const uint32_t> columns, const std::vector<Vec3>& points,
                            uint64_t seed, RowAccumulator& row) {
  const PatchMesh& mesh = *context.mesh;
  uint64_t rays = 0;
  for (uint32_t j : columns) {
    if (!PatchesCanExchange(mesh, i, j)) continue;
    row.Add(j, AnalyticPairFormFactor(context, i, points, j, seed, rays));
  }
  return rays;
}

std::vector<uint32_t> EmitterPatches(const RowContext& context) {
  std::vector<uint32_t> emitters;
  for (uint32_t j = 0; j < context.emitter.size(); ++j) {
    if (context.emitter[j]) emitters.push_back(j);
  }
  return emitters;
}

}  // namespace radflux
