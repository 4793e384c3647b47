#include "solver/formfactor/analytic_pair.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "solver/core/sampling.h"
#include "solver/formfactor/polygon_form_factor.h"

namespace radflux {
namespace {

// Pattern streams, so the samples of different purposes are independent.
constexpr uint64_t kPointStream = 1;
constexpr uint64_t kTargetStream = 2;

// A patch (<= 4 vertices) clipped by one plane (<= 5, or up to 8 for a sliver along the
// plane, see ClipPolygonToHalfSpace): fixed storage, no allocation.
struct SmallPolygon {
  std::array<Vec3, 8> vertex;
  size_t size = 0;
  std::span<const Vec3> View() const { return {vertex.data(), size}; }
};

// cos(theta_x) cos(theta_y) / r^2 of the pair (x, y), the form-factor kernel up to pi,
// into `kernel`; false when either point is behind the other's plane (decided before the
// division, so that the caller's branch does not wait for it).
bool PairKernel(const Vec3& x, const Vec3& nx, const Vec3& y, const Vec3& ny, double& kernel) {
  const Vec3 d = y - x;
  const double cx = Dot(nx, d), cy = -Dot(ny, d);
  if (!(cx > 0 && cy > 0)) return false;
  const double r2 = Dot(d, d);
  kernel = cx * cy / (r2 * r2);
  return true;
}

// A shadow ray between two surface points, each lifted off its surface by the epsilon;
// t in (0, 1 - 1e-6) along target - origin.
StreamRay ShadowRay(const RowContext& context, const Vec3& x, const Vec3& nx, const Vec3& y,
                    const Vec3& ny) {
  return StreamRay::Segment(x + nx * context.ray_epsilon, y + ny * context.ray_epsilon);
}

// Patch `of` against the plane of patch `plane`: its corners' distances along the plane's
// normal from its centroid, whether some corner is in front by more than the plane's
// margin, and whether none is behind (so that clipping would keep `of` whole). Four
// corners always: a triangle's fourth repeats its third, which changes neither answer.
struct Facing {
  std::array<double, 4> distance;
  bool any_front = false, all_front = true;
};

Facing FacePlane(const PairPatch& of, const PairPatch& plane) {
  Facing f;
  for (size_t k = 0; k < 4; ++k) {
    f.distance[k] = Dot(of.corner[k] - plane.centroid, plane.normal);
    f.any_front |= f.distance[k] > plane.front_margin;  // no branches: | and &, not || and &&
    f.all_front &= f.distance[k] >= 0;
  }
  return f;
}

// One pair's estimate before its shadow rays are traced: the mean exact unoccluded form
// factor, and the kernel weight of each of its rays (appended to a shared batch).
struct PairPlan {
  uint32_t j = 0;
  double unoccluded = 0;  // mean over the points of the exact point-to-polygon F
  size_t first_ray = 0, ray_count = 0;
};

// Scratch of one thread's pairs: their plans, shadow rays and the rays' kernel weights.
struct PairBatch {
  std::vector<PairPlan> plans;
  std::vector<StreamRay> rays;
  std::vector<double> kernels;
  std::vector<Point2> targets;  // one pair's target pattern on [0,1)^2
  SmallPolygon clipped;         // one pair's target clipped to the receiver's plane
};

// Sets up F_ij (see AnalyticPairs::FormFactor) for a pair that can exchange light, with
// j's corners `facing` i's plane: its unoccluded mean and its shadow rays, appended to
// `batch` with their kernel weights. The contour integrals of an unclipped j come from
// `contours` when given (begun on this row and these points).
PairPlan PlanPair(const RowContext& context, const PairPatches& patches, uint32_t i,
                  const std::vector<Vec3>& points, uint32_t j, const Facing& facing, uint64_t seed,
                  PairBatch& batch, ContourCache* contours) {
  const PairPatch& pi = patches[i];
  const PairPatch& pj = patches[j];
  std::vector<StreamRay>& rays = batch.rays;
  std::vector<double>& kernels = batch.kernels;
  PairPlan plan;
  plan.j = j;
  plan.first_ray = rays.size();
  // All points of i share i's plane, so clip j against it once (when it is not whole
  // in front of it).
  std::span<const Vec3> polygon(pj.corner.data(), pj.corners);
  if (!facing.all_front) {
    SmallPolygon& clipped = batch.clipped;
    clipped.size = ClipPolygonToHalfSpace(
        polygon, std::span<const double>(facing.distance.data(), pj.corners), clipped.vertex);
    if (clipped.size < 3) return plan;
    polygon = clipped.View();
  }
  ContourCache* shared = facing.all_front ? contours : nullptr;
  const uint32_t pattern = PatternSeed(seed ^ (uint64_t{i} << 32), j, kTargetStream);
  const size_t s = points.size();
  const PatchPointSampler& sample_target = patches.Sampler(j);
  std::span<Point2> targets(batch.targets.data(), s);
  MultiJitteredSamples(pattern, targets);
  double f = 0, unoccluded = 0;
  for (size_t m = 0; m < s; ++m) {
    // A point behind j's plane sees only j's back: no exchange from there (this matters
    // where i runs under a solid, e.g. floor patches partly beneath a block).
    if (Dot(points[m] - pj.centroid, pj.normal) <= 0) continue;
    // Repeated points (hemicube: s copies of the centroid) share one contour integral.
    if (m == 0 || !(points[m] == points[m - 1])) {
      f = shared ? shared->FormFactor(j, m)
                 : UnclippedPointToPolygonFormFactor(points[m], pi.normal, polygon);
    }
    unoccluded += f;
    const Vec3 target = sample_target(targets[m]);
    double kernel;
    if (!PairKernel(points[m], pi.normal, target, pj.normal, kernel)) continue;
    rays.push_back(ShadowRay(context, points[m], pi.normal, target, pj.normal));
    kernels.push_back(kernel);
  }
  plan.unoccluded = unoccluded / static_cast<double>(s);
  if (plan.unoccluded <= 0) {  // nothing to see: no rays needed
    rays.resize(plan.first_ray);
    kernels.resize(plan.first_ray);
    return plan;
  }
  if (rays.size() == plan.first_ray) {
    // Every sampled target lay behind i's plane: one ray to the visible part's centre.
    Vec3 centre;
    for (const Vec3& p : polygon) centre += p / static_cast<double>(polygon.size());
    rays.push_back(ShadowRay(context, points[0], pi.normal, centre, pj.normal));
    kernels.push_back(1);
  }
  plan.ray_count = rays.size() - plan.first_ray;
  return plan;
}

// F_ij of a planned pair once its rays are traced: the unoccluded mean times the
// kernel-weighted visible fraction, times j's opacity (`mesh`'s Patch::opacity: a ray
// from i meets j's opaque part only).
double FinishPair(const PatchMesh& mesh, const PairPlan& plan, const std::vector<double>& kernels,
                  const std::vector<StreamRay>& rays) {
  if (plan.unoccluded <= 0) return 0;
  double weight = 0, visible = 0;
  for (size_t r = plan.first_ray; r < plan.first_ray + plan.ray_count; ++r) {
    weight += kernels[r];
    if (!rays[r].Occluded()) visible += kernels[r];
  }
  if (!(weight > 0)) return 0;  // the kernels underflowed
  return plan.unoccluded * (visible / weight) * mesh.patches[plan.j].opacity;
}

}  // namespace

std::vector<Vec3> PatchSamplePoints(const PatchMesh& mesh, uint32_t i, int s, uint64_t seed) {
  std::vector<Point2> u(static_cast<size_t>(s));
  MultiJitteredSamples(PatternSeed(seed, i, kPointStream), u);
  std::vector<Vec3> points;
  const PatchPointSampler sample_point(mesh, i);
  for (const Point2& v : u) points.push_back(sample_point(v));
  return points;
}

AnalyticPairs::AnalyticPairs(const RowContext& context)
    : context_(context), patches_(*context.mesh) {}

bool AnalyticPairs::CanExchange(uint32_t i, uint32_t j) const {
  return i != j && FacePlane(patches_[j], patches_[i]).any_front &&
         FacePlane(patches_[i], patches_[j]).any_front;
}

double AnalyticPairs::FormFactor(uint32_t i, const std::vector<Vec3>& points, uint32_t j,
                                 uint64_t seed, uint64_t& rays) const {
  PairBatch batch;
  batch.targets.resize(points.size());
  const PairPlan plan = PlanPair(context_, patches_, i, points, j,
                                 FacePlane(patches_[j], patches_[i]), seed, batch, nullptr);
  context_.caster->OccludedStream(batch.rays);
  rays += batch.rays.size();
  return FinishPair(*context_.mesh, plan, batch.kernels, batch.rays);
}

uint64_t AnalyticPairs::AddColumns(uint32_t i, std::span<const uint32_t> columns, int samples,
                                   uint64_t seed, RowAccumulator& row) const {
  return AddColumns(i, columns, PatchSamplePoints(*context_.mesh, i, samples, seed), seed, row);
}

uint64_t AnalyticPairs::AddColumns(uint32_t i, std::span<const uint32_t> columns,
                                   const std::vector<Vec3>& points, uint64_t seed,
                                   RowAccumulator& row, ContourCache* contours) const {
  // Per-thread scratch reused row to row: pairs are planned until their shadow rays make
  // a stream of kStreamRays, which is traced and finished before the next pairs are planned
  // (a whole analytic row's rays would not stay in cache between planning and finishing).
  constexpr size_t kStreamRays = 512;
  thread_local PairBatch batch;
  batch.targets.resize(points.size());
  uint64_t traced = 0;
  auto trace_planned = [&] {
    context_.caster->OccludedStream(batch.rays);
    for (const PairPlan& plan : batch.plans) {
      row.Add(plan.j, FinishPair(*context_.mesh, plan, batch.kernels, batch.rays));
    }
    traced += batch.rays.size();
    batch.plans.clear();
    batch.rays.clear();
    batch.kernels.clear();
  };
  const PairPatch& pi = patches_[i];
  for (uint32_t j : columns) {
    if (j == i) continue;
    const Facing facing = FacePlane(patches_[j], pi);
    if (!facing.any_front || !FacePlane(pi, patches_[j]).any_front) continue;
    batch.plans.push_back(
        PlanPair(context_, patches_, i, points, j, facing, seed, batch, contours));
    if (batch.rays.size() >= kStreamRays) trace_planned();
  }
  trace_planned();
  return traced;
}

std::vector<uint32_t> EmitterPatches(const RowContext& context) {
  std::vector<uint32_t> emitters;
  for (uint32_t j = 0; j < context.emitter.size(); ++j) {
    if (context.emitter[j]) emitters.push_back(j);
  }
  return emitters;
}

}  // namespace radflux
