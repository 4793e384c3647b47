#include "solver/formfactor/exposed_area.h"

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

// The number of `points` stratified points of unknown u that are enclosed (pass: the first
// look or the count; their patterns differ).
int EnclosedPoints(const RowContext& context, uint32_t u, int points, uint64_t pass,
                   std::vector<StreamRay>& stream, std::vector<StreamRay>& probes) {
  const uint32_t point_pattern = PatternSeed(kExposureSeed + pass, u, kPointStream);
  const uint32_t direction_pattern = PatternSeed(kExposureSeed + pass, u, kDirectionStream);
  const uint32_t probe_pattern = PatternSeed(kExposureSeed + pass, u, kProbeStream);
  const UnknownPointSampler sample_point(*context.mesh, context.clusters, u);
  const uint32_t n = static_cast<uint32_t>(points);
  std::vector<SurfacePoint> at(n);
  stream.resize(n);
  for (uint32_t r = 0; r < n; ++r) {
    at[r] = sample_point(MultiJitteredSample(r, n, point_pattern));
    stream[r] = context.CosineRay(
        at[r], MultiJitteredSample(PermuteIndex(r, n, direction_pattern), n, direction_pattern));
  }
  context.caster->IntersectStream(stream);
  probes.clear();
  std::vector<uint32_t> owner;
  for (uint32_t r = 0; r < n; ++r) {
    if (!MeetsSolidBack(stream[r], *context.mesh)) continue;
    for (uint32_t q = 1; q < kExposureProbes; ++q) {
      const uint32_t index = r * kExposureProbes + q;
      probes.push_back(context.CosineRay(at[r], {RandomFloat(2 * index, probe_pattern),
                                                 RandomFloat(2 * index + 1, probe_pattern)}));
      owner.push_back(r);
    }
  }
  if (probes.empty()) return 0;
  context.caster->IntersectStream(probes);
  std::vector<uint8_t> open(n, 0);
  for (size_t q = 0; q < probes.size(); ++q) {
    if (!MeetsSolidBack(probes[q], *context.mesh)) open[owner[q]] = 1;
  }
  int enclosed = 0;
  for (uint32_t r = 0; r < n; ++r) {
    enclosed += MeetsSolidBack(stream[r], *context.mesh) && !open[r];
  }
  return enclosed;
}

}  // namespace

bool MeetsSolidBack(const StreamRay& ray, const PatchMesh& mesh) {
  return ray.geom != kNoPatch && ray.FrontPatch() == kNoPatch &&
         mesh.patches[ray.prim].opacity >= 1;
}

std::vector<float> UnknownExposure(const RowContext& context, int threads) {
  const uint32_t unknowns = context.Unknowns();
  std::vector<float> exposure(unknowns, 1.0f);
  std::atomic<bool> any{false};
  ParallelFor(unknowns, 16, threads, [&](int64_t begin, int64_t end) {
    thread_local std::vector<StreamRay> stream, probes;
    for (int64_t v = begin; v < end; ++v) {
      const uint32_t u = static_cast<uint32_t>(v);
      if (!context.needs_row[u]) continue;
      if (EnclosedPoints(context, u, kExposureFirstPoints, 0, stream, probes) == 0) continue;
      const int enclosed = EnclosedPoints(context, u, kExposurePoints, 1, stream, probes);
      if (enclosed == 0 || enclosed == kExposurePoints) continue;
      exposure[u] = static_cast<float>(kExposurePoints - enclosed) / kExposurePoints;
      any = true;
    }
  });
  if (!any) exposure.clear();
  return exposure;
}

}  // namespace radflux
