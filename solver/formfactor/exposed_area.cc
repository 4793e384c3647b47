#include "solver/formfactor/exposed_area.h"

#include <algorithm>
#include <atomic>
#include <span>

#include "solver/core/parallel.h"
#include "solver/core/sampling.h"

namespace radflux {
namespace {

// Pattern streams of the probes' points and directions, apart from every row's.
constexpr uint64_t kExposureSeed = 0xe4c105edull;
constexpr uint64_t kPointStream = 31;
constexpr uint64_t kDirectionStream = 37;
constexpr uint64_t kProbeStream = 41;

// Whether a ray's hit is a back side that closes a solid: a front hit, a miss and a hit on a
// partly transparent patch (an alpha cut-out is a sheet, not a wall) are not.
bool MeetsSolidBack(const StreamRay& ray, const PatchMesh& mesh) {
  return ray.geom != kNoPatch && ray.FrontPatch() == kNoPatch &&
         mesh.patches[ray.prim].opacity >= 1;
}

// Per-thread scratch of EnclosedPoints, reused unknown to unknown.
struct Scratch {
  std::vector<SurfacePoint> at;
  std::vector<StreamRay> stream, probes;
  std::vector<uint32_t> owner;  // per probe, the point it starts from
  std::vector<uint8_t> closed;  // per point, whether every ray so far met a solid's back
};

// A stratified set of n points on [0, 1)^2, drawn once per process: each unknown moves it by
// a shift of its own (Cranley-Patterson), which keeps it stratified at two additions a point.
std::span<const Point2> SharedSet(size_t n, uint64_t stream) {
  static const auto draw = [](size_t count, uint64_t which) {
    std::vector<Point2> set(count);
    MultiJitteredSamples(PatternSeed(kExposureSeed, count, which), set);
    return set;
  };
  static const std::vector<Point2> first_points = draw(kExposureFirstPoints, kPointStream),
                                   first_directions = draw(kExposureFirstPoints, kDirectionStream),
                                   points = draw(kExposurePoints, kPointStream),
                                   directions = draw(kExposurePoints, kDirectionStream);
  if (n == kExposureFirstPoints) return stream == kPointStream ? first_points : first_directions;
  return stream == kPointStream ? points : directions;
}

// The number of `points` (kExposureFirstPoints or kExposurePoints) stratified points of
// unknown u that are enclosed (pass: the first look or the count; their shifts differ).
int EnclosedPoints(const RowContext& context, uint32_t u, int points, uint64_t pass, Scratch& s) {
  const uint64_t seed = kExposureSeed + pass;
  const size_t n = static_cast<size_t>(points);
  const std::span<const Point2> on_patch = SharedSet(n, kPointStream);
  const std::span<const Point2> directions = SharedSet(n, kDirectionStream);
  const Point2 point_shift = RandomShift(PatternSeed(seed, u, kPointStream));
  const Point2 direction_shift = RandomShift(PatternSeed(seed, u, kDirectionStream));
  const uint32_t probe_pattern = PatternSeed(seed, u, kProbeStream);
  const UnknownPointSampler sample_point(*context.mesh, context.clusters, u);
  s.at.resize(n);
  s.stream.resize(n);
  for (size_t r = 0; r < n; ++r) {
    s.at[r] = sample_point(CranleyPattersonShift(on_patch[r], point_shift));
    s.stream[r] = context.CosineRay(s.at[r], CranleyPattersonShift(directions[r], direction_shift));
  }
  context.caster->IntersectStream(s.stream);
  s.closed.resize(n);
  s.probes.clear();
  s.owner.clear();
  for (size_t r = 0; r < n; ++r) {
    s.closed[r] = MeetsSolidBack(s.stream[r], *context.mesh);
    if (!s.closed[r]) continue;
    for (uint32_t q = 1; q < kExposureProbes; ++q) {
      const uint32_t index = static_cast<uint32_t>(r) * kExposureProbes + q;
      s.probes.push_back(context.CosineRay(s.at[r], {RandomFloat(2 * index, probe_pattern),
                                                     RandomFloat(2 * index + 1, probe_pattern)}));
      s.owner.push_back(static_cast<uint32_t>(r));
    }
  }
  if (s.probes.empty()) return 0;
  context.caster->IntersectStream(s.probes);
  for (size_t q = 0; q < s.probes.size(); ++q) {
    if (!MeetsSolidBack(s.probes[q], *context.mesh)) s.closed[s.owner[q]] = 0;
  }
  return static_cast<int>(std::count(s.closed.begin(), s.closed.end(), 1));
}

}  // namespace

std::vector<float> UnknownExposure(const RowContext& context, int threads) {
  const uint32_t unknowns = context.Unknowns();
  std::vector<float> exposure(unknowns, 1.0f);
  std::atomic<bool> any{false};
  ParallelFor(unknowns, 16, threads, [&](int64_t begin, int64_t end) {
    thread_local Scratch scratch;
    for (int64_t v = begin; v < end; ++v) {
      const uint32_t u = static_cast<uint32_t>(v);
      if (!context.needs_row[u] || context.emitter[u]) continue;
      if (EnclosedPoints(context, u, kExposureFirstPoints, 0, scratch) == 0) continue;
      const int enclosed = EnclosedPoints(context, u, kExposurePoints, 1, scratch);
      if (enclosed == 0 || enclosed == kExposurePoints) continue;
      exposure[u] = static_cast<float>(kExposurePoints - enclosed) / kExposurePoints;
      any = true;
    }
  });
  if (!any) exposure.clear();
  return exposure;
}

}  // namespace radflux
