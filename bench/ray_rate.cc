// ray_rate [PATCHES]: rays per second of each form-factor builder on the Cornell box
// against Embree's own rate for the same rays in a bare rtcIntersect1 / rtcOccluded1
// loop on this machine. Median of 5 runs each; one line per method.
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
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

template <typename F>
double MedianSeconds(F f) {
  std::vector<double> t;
  for (int r = 0; r < 5; ++r) {
    const auto s = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count());
  }
  return Median(t);
}

// The bare loop: rays from patch centroids in cosine-weighted directions, traced with
// rtcIntersect1 (closest hit, as monte_carlo and hemicube do) or rtcOccluded1.
double BareRate(RTCScene scene, const PatchMesh& mesh, bool occluded, int per_patch) {
  std::vector<RTCRayHit> rays;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Frame frame = Frame::FromNormal(mesh.patches[p].normal);
    for (int k = 0; k < per_patch; ++k) {
      const Vec3 d = frame.ToWorld(SampleCosineHemisphere(MultiJitteredSample(k, per_patch, p)));
      const Vec3 o = mesh.patches[p].centroid + mesh.patches[p].normal * 0.01;
      RTCRayHit rh{};
      rh.ray = {float(o.x), float(o.y), float(o.z), 0.f, float(d.x), float(d.y), float(d.z), 0.f,
                occluded ? 500.f : 1e30f, 0xffffffffu, 0, 0};
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rays.push_back(rh);
    }
  }
  const double seconds = MedianSeconds([&] {
#pragma omp parallel for schedule(dynamic, 1024)
    for (size_t i = 0; i < rays.size(); ++i) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      RTCRayHit rh = rays[i];
      if (occluded) {
        rtcOccluded1(scene, &context, &rh.ray);
      } else {
        rtcIntersect1(scene, &context, &rh);
      }
    }
  });
  return rays.size() / seconds;
}

int Run(int patches) {
  absl::StatusOr<Scene> scene = LoadObjFile(RADFLUX_SOURCE_DIR "/scenes/cornell_box.obj");
  JobOptions options;
  options.mesh.target_patches = patches;
  auto job = PrepareJob(*scene, options);
  if (!job.ok()) return 1;
  const PatchMesh& mesh = (*job)->mesh;
  const double bare_hit = BareRate((*job)->caster->scene(), mesh, false, 64);
  const double bare_occ = BareRate((*job)->caster->scene(), mesh, true, 64);
  std::printf("patches %zu threads %d\nbare rtcIntersect1 %.3g rays/s, bare rtcOccluded1 %.3g rays/s\n",
              mesh.size(), DefaultThreadCount(), bare_hit, bare_occ);
  struct Case { FormFactorMethod method; int knob; double bare; };
  for (const Case& c : {Case{FormFactorMethod::kMonteCarlo, 64, bare_hit},
                        Case{FormFactorMethod::kHemicube, 8, bare_hit},
                        Case{FormFactorMethod::kAnalytic, 1, bare_occ}}) {
    FormFactorOptions f;
    f.method = c.method;
    f.rays = c.knob;
    f.hemicube_res = c.knob;
    f.samples = c.knob;
    RowContext context = (*job)->rows;
    if (c.method == FormFactorMethod::kMonteCarlo) context.emitter.assign(mesh.size(), 0);
    if (c.method == FormFactorMethod::kAnalytic) {  // O(n^2): time every 50th row only
      for (size_t p = 0; p < mesh.size(); ++p) context.needs_row[p] = p % 50 == 0;
    }
    uint64_t rays = 0;
    const double seconds = MedianSeconds([&] { rays = BuildFormFactors(context, f)->stats.rays; });
    const double rate = rays / seconds;
    std::printf("%-12s knob %3d: %.3g rays/s = %.0f%% of bare Embree (%.3f s for %llu rays)\n",
                std::string(MethodName(c.method)).c_str(), c.knob, rate, 100 * rate / c.bare,
                seconds, static_cast<unsigned long long>(rays));
  }
  return 0;
}

}  // namespace
}  // namespace radflux

int main(int argc, char** argv) { return radflux::Run(argc > 1 ? std::atoi(argv[1]) : 10000); }
