// monte_carlo: k cosine-weighted rays from stratified points on patch i; each ray
// that hits the front of patch j adds 1/k to F_ij. Emitter columns come from light
// sampling instead (their direct light would be the noisiest term): a fixed budget of
// light samples per row, whatever the number of emitter patches (light_sampling.h). MC
// hits on emitters are dropped, so the two never double count.
#include <vector>

#include "solver/core/sampling.h"
#include "solver/formfactor/builders.h"
#include "solver/formfactor/light_sampling.h"

namespace radflux {
namespace {

constexpr uint64_t kShiftStream = 11;
constexpr uint32_t kPositionPattern = 0x2545f491u;
constexpr uint32_t kDirectionPattern = 0x9e3779b9u;

class MonteCarloBuilder final : public RowBuilder {
 public:
  // The k position samples and k paired direction samples are one correlated
  // multi-jittered set, computed once; each patch shifts both toroidally by its own
  // random offsets (Cranley-Patterson rotation), which keeps them stratified and
  // makes the estimate unbiased at a few additions per ray.
  MonteCarloBuilder(const RowContext& context, const FormFactorOptions& options)
      : context_(context), options_(options), lights_(context) {
    const uint32_t k = static_cast<uint32_t>(options.rays);
    for (uint32_t r = 0; r < k; ++r) {
      positions_.push_back(MultiJitteredSample(r, k, kPositionPattern));
      const Point2 d =
          MultiJitteredSample(PermuteIndex(r, k, kDirectionPattern), k, kDirectionPattern);
      direction_x_.push_back(static_cast<float>(d.x));
      direction_y_.push_back(static_cast<float>(d.y));
    }
  }

  uint64_t BuildRow(uint32_t i, RowAccumulator& row) const override {
    const uint32_t shift = PatternSeed(options_.seed, i, kShiftStream);
    const Point2 ps = RandomShift(shift, 0);
    const Point2 ds = RandomShift(shift, 2);
    thread_local std::vector<StreamRay> stream;  // per-thread scratch, reused row to row
    stream.resize(positions_.size());
    if (context_.SinglePatch(i)) {
      PatchRays(context_.FirstPatch(i), ps, ds, stream);
    } else {
      GroupRays(i, ps, ds, stream);
    }
    context_.caster->IntersectStream(stream);
    const double weight = 1.0 / static_cast<double>(positions_.size());
    for (const StreamRay& ray : stream) {
      const uint32_t hit = ray.FrontPatch();  // a back side absorbs the ray
      if (hit == kNoPatch) continue;
      const uint32_t j = context_.UnknownOf(hit);  // a group's hits on itself: see face_grouping.h
      if (j != i && !context_.emitter[j]) row.Add(j, weight);
    }
    // A group's irradiance varies across its members far more than across one patch (some
    // face a lamp, some do not): its light samples each take a point of their own, so the
    // budget is spread over the whole group instead of a few spots that mostly miss the lit ones.
    const bool group = !context_.SinglePatch(i);
    const int per_point = group ? 1 : kLightSamplesAtAPoint;
    const uint64_t light_rays = lights_.AddEmitterColumns(
        i, options_.samples * (kLightSamplesPerS / per_point), per_point, options_.seed, row);
    // The two parts are independent estimates: where emitters fill much of the hemisphere
    // their noise can add up to more than 1. Only a row that would then return more light
    // than kMaxRowGain is scaled back (rho F B must converge for every rho < 1): scaling
    // every row above 1 cut the upper half of a closed room's rows' noise (they sum to 1 in
    // expectation) and made B 1.1% low in a closed cube at k = 64 (3% at k = 16).
    double sum = 0;
    for (uint32_t j : row.Touched()) sum += row.Value(j);
    const double limit = context_.MaxRowSum(i);
    if (sum > limit) row.Scale(limit / sum);
    return stream.size() + light_rays;
  }

 private:
  // The k rays of one patch p, shifted by (ps, ds).
  void PatchRays(uint32_t p, Point2 ps, Point2 ds, std::vector<StreamRay>& stream) const {
    const PatchMesh& mesh = *context_.mesh;
    const Patch& patch = mesh.patches[p];
    const Frame frame = Frame::FromNormal(patch.normal);
    const Vec3 lift = patch.normal * context_.ray_epsilon;
    const size_t k = positions_.size();
    // The k directions first, in float and in a loop of their own, which GCC vectorises
    // (this file is built with -fno-math-errno for the sqrt): per-thread scratch, x then y
    // then z, reused row to row.
    thread_local std::vector<float> directions;
    directions.resize(3 * k);
    float* __restrict wx = directions.data();
    float* __restrict wy = wx + k;
    float* __restrict wz = wy + k;
    const float* ux = direction_x_.data();
    const float* uy = direction_y_.data();
    const float dsx = static_cast<float>(ds.x), dsy = static_cast<float>(ds.y);
    const auto f = [](double v) { return static_cast<float>(v); };
    const float sx = f(frame.s.x), sy = f(frame.s.y), sz = f(frame.s.z);
    const float tx = f(frame.t.x), ty = f(frame.t.y), tz = f(frame.t.z);
    const float nx = f(frame.n.x), ny = f(frame.n.y), nz = f(frame.n.z);
    for (size_t r = 0; r < k; ++r) {
      float x, y, z;
      CosineHemisphereDirection(WrapShift(ux[r], dsx), WrapShift(uy[r], dsy), x, y, z);
      wx[r] = sx * x + tx * y + nx * z;
      wy[r] = sy * x + ty * y + ny * z;
      wz[r] = sz * x + tz * y + nz * z;
    }
    const PatchPointSampler sample_point(mesh, p);
    for (size_t r = 0; r < k; ++r) {
      StreamRay& ray = stream[r];
      ray.SetOrigin(sample_point(CranleyPattersonShift(positions_[r], ps)) + lift);
      ray.dir_x = wx[r], ray.dir_y = wy[r], ray.dir_z = wz[r];
      ray.ResetHit();
    }
  }

  // The k rays of a group of patches: each ray's origin is drawn over the members by area
  // (UnknownPointSampler) and its direction is cosine-weighted about that member's normal.
  void GroupRays(uint32_t u, Point2 ps, Point2 ds, std::vector<StreamRay>& stream) const {
    const UnknownPointSampler sample_point(*context_.mesh, context_.clusters, u);
    for (size_t r = 0; r < positions_.size(); ++r) {
      const SurfacePoint at = sample_point(CranleyPattersonShift(positions_[r], ps));
      const Vec3 w = Frame::FromNormal(at.n).ToWorld(SampleCosineHemisphere(
          {WrapShift(double{direction_x_[r]}, ds.x), WrapShift(double{direction_y_[r]}, ds.y)}));
      StreamRay& ray = stream[r];
      ray.SetOrigin(at.x + at.n * context_.ray_epsilon);
      ray.SetDirection(w);
      ray.ResetHit();
    }
  }

  const RowContext& context_;
  FormFactorOptions options_;
  LightSampler lights_;  // the emitter columns
  std::vector<Point2> positions_;
  std::vector<float> direction_x_, direction_y_;  // the unshifted direction samples, in float
};

}  // namespace

std::unique_ptr<RowBuilder> MakeMonteCarloBuilder(const RowContext& context,
                                                  const FormFactorOptions& options) {
  return std::make_unique<MonteCarloBuilder>(context, options);
}

}  // namespace radflux
