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
  const double eps = context.ray_epsilon;
  double sum = 0;
  for (int m = 0; m < s; ++m) {
    const double f = UnclippedPointToPolygonFormFactor(points[m], pi.normal, polygon);
    if (f <= 0) continue;
    const Vec3 target = SamplePatchPoint(mesh, j, MultiJitteredSample(m, s, pattern)) +
                        pj.normal * eps;
    const Vec3 origin = points[m] + pi.normal * eps;
    ++rays;
    if (!context.caster->Occluded({origin, target - origin, 0, 1 - 1e-6})) sum += f;
  }
  return sum / s;
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
