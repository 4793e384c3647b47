// reference_image [--emit MATERIAL=R,G,B ...] SCENE OUT.pfm PATHS_PER_PIXEL SEED
//     --pos X,Y,Z --look X,Y,Z [--up X,Y,Z] [--fov DEG] [--size WxH]
// A path-traced picture of a scene under radflux's conventions by bench/reference_paths'
// tracer (nothing of the radiosity solver: the loader's faces, Embree, light sampling at
// every vertex), for checking a radflux picture region by region where Cycles is not at hand
// or to tell apart what the two conventions do (issue 21). Each pixel averages its paths at
// uniformly jittered points: radiance (E + rho H) / pi of the first front side met, 0 on a
// miss or a back side. The camera is radflux's (--camera-pos, --camera-look-at, --camera-up,
// --fov-deg vertical, default 60 degrees, 160x120). Checked on the conference room (issue
// camera): 64 paths a pixel, 9 s on 2 threads, regions within 0.5% of Cycles at 2 x 512
// samples but the left wall's 1.5% (noise: its seeds spread 0.4%).
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>

#include "bench/reference_paths.h"
#include "solver/output/camera.h"
#include "solver/output/image.h"
#include "solver/scene/import_options.h"
#include "solver/scene/load_scene.h"

namespace radflux {
namespace {

constexpr int kGuideParticles = 1 << 20;

bool ParseVec3(const char* text, Vec3& v) {
  return std::sscanf(text, "%lf,%lf,%lf", &v.x, &v.y, &v.z) == 3;
}

int Run(const ImportOptions& import, const std::string& scene_path, const std::string& out,
        int paths, uint64_t seed, Camera camera) {
  auto scene = LoadScene(scene_path, import);
  if (!scene.ok()) return std::fprintf(stderr, "%s\n", scene.status().ToString().c_str()), 1;
  auto tracer = ReferenceTracer::Create(*scene);
  if (!tracer.ok()) return std::fprintf(stderr, "%s\n", tracer.status().ToString().c_str()), 1;
  (*tracer)->SetGuide(ParticleGuide(**tracer, seed, kGuideParticles));
  auto caster = EmbreeRayCaster::Create((*tracer)->mesh());
  if (!caster.ok()) return std::fprintf(stderr, "%s\n", caster.status().ToString().c_str()), 1;
  camera.position = camera.position - scene->origin;  // the loader recentres the scene
  camera.look_at = camera.look_at - scene->origin;
  if (absl::Status s = ValidateCamera(camera); !s.ok())
    return std::fprintf(stderr, "%s\n", s.ToString().c_str()), 2;
  const PinholeProjection projection(camera);
  Image image(camera.width, camera.height);
#pragma omp parallel for schedule(dynamic)
  for (int y = 0; y < camera.height; ++y) {
    ReferenceRng rng(seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(y));
    std::uniform_real_distribution<double> jitter(0, 1);
    for (int x = 0; x < camera.width; ++x) {
      Rgb sum{};
      for (int s = 0; s < paths; ++s) {
        const Ray ray = projection.RayThrough(x + jitter(rng), y + jitter(rng));
        const Hit hit = (*caster)->Intersect(ray);
        if (hit.patch == kNoPatch || Dot(hit.normal, ray.direction) >= 0) continue;
        const Rgb b =
            (*tracer)->ReflectedRadiosity(hit.patch, ray.origin + ray.direction * hit.t, rng);
        const Rgb& e = (*tracer)->MaterialOf(hit.patch).emission;
        for (int c = 0; c < kBands; ++c) sum[c] += (b[c] + e[c]) / std::numbers::pi;
      }
      for (int c = 0; c < kBands; ++c) image.Pixel(x, y)[c] = static_cast<float>(sum[c] / paths);
    }
  }
  if (absl::Status s = WritePfm(out, image); !s.ok())
    return std::fprintf(stderr, "%s\n", s.ToString().c_str()), 1;
  return 0;
}

}  // namespace
}  // namespace radflux

int main(int argc, char** argv) {
  radflux::ImportOptions import;
  radflux::Camera camera;
  camera.vertical_fov_degrees = 60;
  camera.width = 160, camera.height = 120;
  bool placed = false;
  std::vector<const char*> positional;
  const int first = radflux::TakeEmitFlags(argc, argv, import);
  if (first < 0) return 2;
  for (int k = first; k < argc; ++k) {
    const std::string flag = argv[k];
    const bool has_value = k + 1 < argc;
    bool ok = true;
    if (flag == "--pos" && has_value) {
      ok = radflux::ParseVec3(argv[++k], camera.position);
      placed = true;
    } else if (flag == "--look" && has_value) {
      ok = radflux::ParseVec3(argv[++k], camera.look_at);
    } else if (flag == "--up" && has_value) {
      ok = radflux::ParseVec3(argv[++k], camera.up);
    } else if (flag == "--fov" && has_value) {
      camera.vertical_fov_degrees = std::atof(argv[++k]);
    } else if (flag == "--size" && has_value) {
      ok = std::sscanf(argv[++k], "%dx%d", &camera.width, &camera.height) == 2;
    } else {
      positional.push_back(argv[k]);
    }
    if (!ok) return std::fprintf(stderr, "bad value for %s: %s\n", flag.c_str(), argv[k]), 2;
  }
  if (positional.size() != 4 || !placed) {
    std::fprintf(stderr,
                 "usage: reference_image [--emit MATERIAL=R,G,B ...] SCENE OUT.pfm PATHS_PER_PIXEL "
                 "SEED --pos X,Y,Z --look X,Y,Z [--up X,Y,Z] [--fov DEG] [--size WxH]\n");
    return 2;
  }
  return radflux::Run(import, positional[0], positional[1], std::atoi(positional[2]),
                      std::strtoull(positional[3], nullptr, 10), camera);
}
