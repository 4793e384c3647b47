// ray_rate [PATCHES]: rays per second of each form-factor builder on the Cornell box
// against Embree's own rate for the same kind of rays in a bare rtcIntersect1 /
// rtcOccluded1 loop on this machine. The bare loop and the builder run alternately, 7
// times; the ratio reported is the median of the 7 per-pair ratios (robust to a shared,
// noisy machine), with the median rates beside it.
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "solver/core/parallel.h"
#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"

namespace radflux {
namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double Seconds(const std::function<void()>& f) {
  const auto s = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count();
}

// Records every ray a builder casts (then forwards it), so that the bare loop can
// trace exactly the same rays.
class RecordingCaster final : public RayCaster {
 public:
  explicit RecordingCaster(const RayCaster& inner) : inner_(inner) {}
  Hit Intersect(const Ray& ray) const override { return Record(ray, false), inner_.Intersect(ray); }
  bool Occluded(const Ray& ray) const override { return Record(ray, true), inner_.Occluded(ray); }
  void IntersectStream(std::span<StreamRay> rays) const override {
    for (const StreamRay& r : rays) {
      Record({{r.org_x, r.org_y, r.org_z}, {r.dir_x, r.dir_y, r.dir_z}, r.t_near, r.t_far}, false);
    }
    inner_.IntersectStream(rays);
  }
  void OccludedStream(std::span<StreamRay> rays) const override {
    for (const StreamRay& r : rays) {
      Record({{r.org_x, r.org_y, r.org_z}, {r.dir_x, r.dir_y, r.dir_z}, r.t_near, r.t_far}, true);
    }
    inner_.OccludedStream(rays);
  }
  std::vector<std::pair<Ray, bool>> recorded;  // (ray, occlusion query)

 private:
  void Record(const Ray& ray, bool occluded) const {
#pragma omp critical(record_ray)
    const_cast<RecordingCaster*>(this)->recorded.push_back({ray, occluded});
  }
  const RayCaster& inner_;
};

// The bare loop: one rtcIntersect1 or rtcOccluded1 per recorded ray, nothing else.
class BareLoop {
 public:
  BareLoop(RTCScene scene, const std::vector<std::pair<Ray, bool>>& rays) : scene_(scene) {
    for (const auto& [ray, occluded] : rays) {
      RTCRayHit rh{};
      rh.ray = {float(ray.origin.x),
                float(ray.origin.y),
                float(ray.origin.z),
                float(ray.t_near),
                float(ray.direction.x),
                float(ray.direction.y),
                float(ray.direction.z),
                0.f,
                std::isinf(ray.t_far) ? 1e30f : float(ray.t_far),
                0xffffffffu,
                0,
                0};
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rays_.push_back(rh);
      occluded_.push_back(occluded);
    }
  }
  // Rays per second of one pass over all rays.
  double Rate() const {
    return rays_.size() / Seconds([&] {
#pragma omp parallel for schedule(dynamic, 1024)
             for (size_t i = 0; i < rays_.size(); ++i) {
               RTCIntersectContext context;
               rtcInitIntersectContext(&context);
               RTCRayHit rh = rays_[i];
               if (occluded_[i]) {
                 rtcOccluded1(scene_, &context, &rh.ray);
               } else {
                 rtcIntersect1(scene_, &context, &rh);
               }
             }
           });
  }

 private:
  RTCScene scene_;
  std::vector<RTCRayHit> rays_;
  std::vector<uint8_t> occluded_;
};

int Run(int patches, const char* only, int knob) {
  absl::StatusOr<Scene> scene = LoadObjFile(RADFLUX_SOURCE_DIR "/scenes/cornell_box.obj");
  JobOptions options;
  options.mesh.target_patches = patches;
  auto job = PrepareJob(*scene, options);
  if (!job.ok()) return 1;
  const PatchMesh& mesh = (*job)->mesh;
  std::printf("patches %zu threads %d\n", mesh.size(), DefaultThreadCount());
  struct Case {
    FormFactorMethod method;
    int knob;
  };
  for (const Case& c :
       {Case{FormFactorMethod::kMonteCarlo, 64}, Case{FormFactorMethod::kHemicube, 8},
        Case{FormFactorMethod::kAnalytic, 1}}) {
    if (only && MethodName(c.method) != only) continue;
    FormFactorOptions f;
    f.method = c.method;
    const int k = knob > 0 ? knob : c.knob;
    f.rays = k;
    f.hemicube_res = k;
    f.samples = k;
    RowContext context = (*job)->rows;
    // Pure ray work: monte_carlo without analytic emitter columns; analytic on every
    // 50th row only (it is O(n^2)).
    if (c.method == FormFactorMethod::kMonteCarlo) context.emitter.assign(mesh.size(), 0);
    if (c.method == FormFactorMethod::kAnalytic) {
      for (size_t p = 0; p < mesh.size(); ++p) context.needs_row[p] = p % 50 == 0;
    }
    RecordingCaster recorder(*(*job)->caster);
    RowContext recording = context;
    recording.caster = &recorder;
    (void)BuildFormFactors(recording, f);
    const BareLoop bare((*job)->caster->scene(), recorder.recorded);
    std::vector<double> ratios, rates, bare_rates;
    uint64_t rays = 0;
    for (int rep = 0; rep < 7; ++rep) {
      bare_rates.push_back(bare.Rate());
      rates.push_back(1 / Seconds([&] { rays = BuildFormFactors(context, f)->stats.rays; }));
      rates.back() *= rays;
      ratios.push_back(rates.back() / bare_rates.back());
    }
    std::printf(
        "%-12s knob %3d: %.3g rays/s, bare Embree %.3g rays/s: %.0f%% (median of 7 pairs)\n",
        std::string(MethodName(c.method)).c_str(), k, Median(rates), Median(bare_rates),
        100 * Median(ratios));
  }
  return 0;
}

}  // namespace
}  // namespace radflux

// Usage: ray_rate [PATCHES [METHOD|all [KNOB]]]
int main(int argc, char** argv) {
  const char* only = argc > 2 && std::string(argv[2]) != "all" ? argv[2] : nullptr;
  return radflux::Run(argc > 1 ? std::atoi(argv[1]) : 10000, only,
                      argc > 3 ? std::atoi(argv[3]) : 0);
}
