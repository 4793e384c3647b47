#include "client/output_flags.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "solver/mesh/patch_attributes.h"
#include "solver/output/default_view.h"
#include "solver/output/final_gather.h"
#include "solver/output/gltf_writer.h"
#include "solver/output/image.h"
#include "solver/output/lightmap_gltf.h"
#include "solver/output/patch_values_csv.h"
#include "solver/output/ply_writer.h"
#include "solver/output/render.h"
#include "solver/output/tone_map.h"
#include "solver/output/vertex_radiosity.h"
#include "solver/raytrace/embree_ray_caster.h"

namespace radflux::cli {
namespace {

absl::Status RequireExtension(const std::string& path, const std::string& flag,
                              std::initializer_list<const char*> extensions) {
  if (path.empty()) return absl::OkStatus();
  std::string list;
  for (const char* e : extensions) {
    if (absl::EndsWith(path, e)) return absl::OkStatus();
    list += std::string(list.empty() ? "" : " or ") + e;
  }
  return absl::InvalidArgumentError(absl::StrCat(flag, " '", path, "': must end in ", list));
}

Vec3 ToVec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

std::pair<int, int> ParseSize(const std::string& size) {
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x') return {0, 0};
  return {w, h};
}

// The picture of --render: with --gather N the final gather; else the direct light per pixel
// over the Gouraud-shaded indirect light where that is known and asked for; else Gouraud-shaded B.
absl::StatusOr<Image> RenderPicture(const OutputFlags& f, const Scene& scene, const PatchMesh& mesh,
                                    const ShadingMesh& shading, const RayCaster& caster,
                                    const std::vector<Rgb>& radiosity,
                                    const std::vector<Rgb>& indirect, const Camera& camera,
                                    uint64_t seed, int threads) {
  GatherOptions options;
  options.threads = threads;
  options.seed = seed;
  if (f.gather > 0) {
    options.rays = f.gather;
    return RenderFinalGather(mesh, shading, caster, ComputePatchAttributes(scene, mesh), radiosity,
                             camera, options);
  }
  if (DrawsDirectPerPixel(f) && !indirect.empty()) {
    options.rays = f.pixel_samples;
    return RenderDirectPerPixel(mesh, shading, caster, ComputePatchAttributes(scene, mesh),
                                radiosity, indirect, camera, options);
  }
  auto vertex_radiosity = VertexRadiosity(mesh, shading, radiosity);
  if (!vertex_radiosity.ok()) return vertex_radiosity.status();
  RenderOptions gouraud;
  gouraud.threads = threads;
  return RenderRadiance(mesh, caster, *vertex_radiosity, camera, gouraud);
}

absl::Status WriteValues(const OutputFlags& f, const Scene& scene, const PatchMesh& mesh,
                         const std::vector<Rgb>& radiosity) {
  if (f.patch_values.empty()) return absl::OkStatus();
  return WritePatchValuesCsv(f.patch_values, scene, mesh, radiosity);
}

// The picture, rendered in the solver's coordinates (single-precision rays near the origin).
absl::Status WriteRender(const OutputFlags& f, const Scene& scene, const PatchMesh& solved_mesh,
                         const ShadingMesh& shading, const std::vector<Rgb>& radiosity,
                         const std::vector<Rgb>& indirect, const ToneMapOptions& tone,
                         uint64_t seed, int threads, OutputTimings* timings) {
  auto caster = EmbreeRayCaster::Create(solved_mesh);
  if (!caster.ok()) return caster.status();
  absl::StatusOr<Camera> camera =
      CameraFromFlags(f, solved_mesh, **caster, radiosity, scene.origin);
  if (!camera.ok()) return camera.status();
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<Image> image = RenderPicture(f, scene, solved_mesh, shading, **caster, radiosity,
                                              indirect, *camera, seed, threads);
  if (!image.ok()) return image.status();
  if (timings != nullptr && f.gather > 0) {
    timings->gather =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return absl::EndsWith(f.render, ".pfm") ? WritePfm(f.render, *image)
                                          : WritePng(f.render, *image, tone);
}

}  // namespace

bool DrawsDirectPerPixel(const OutputFlags& f) {
  return !f.render.empty() && f.gather == 0 && f.direct_light == "pixel";
}

void AddOutputFlags(CLI::App& app, OutputFlags& f) {
  const std::vector<CLI::Option*> added = {
      app.add_option("--out", f.out, "lit mesh: FILE.ply or FILE.glb"),
      app.add_option("--render", f.render, "picture: FILE.png (tone mapped) or FILE.pfm (linear)"),
      app.add_option("--report", f.report, "job report: FILE.json"),
      app.add_option("--patch-values", f.patch_values, "per-patch radiosity: FILE.csv"),
      app.add_option("--camera-pos", f.camera_pos, "camera position X,Y,Z")
          ->delimiter(',')
          ->expected(3),
      app.add_option("--camera-look-at", f.camera_look_at, "point the camera looks at X,Y,Z")
          ->delimiter(',')
          ->expected(3),
      app.add_option("--camera-up", f.camera_up,
                     "camera up vector X,Y,Z (default: the default view's +y or +z; with "
                     "--camera-pos, 0,1,0)")
          ->delimiter(',')
          ->expected(3),
      app.add_option("--fov-deg", f.fov_deg, "vertical field of view, degrees")
          ->capture_default_str(),
      app.add_option("--size", f.size, "image size WxH")->capture_default_str(),
      app.add_option("--exposure", f.exposure,
                     "PNG exposure in stops on top of auto exposure (95th percentile = white)")
          ->capture_default_str(),
      app.add_flag("--linear-png", f.linear_png, "write PNG bytes without the sRGB curve"),
      app.add_option("--metres-per-unit", f.metres_per_unit, "scene unit in metres, for .glb")
          ->capture_default_str(),
      app.add_option("--gather", f.gather,
                     "--render by final gather: N rays per pixel into the solution plus light "
                     "sampled on the emitters (0 = none: see --direct-light)")
          ->capture_default_str(),
      app.add_option("--direct-light", f.direct_light,
                     "--render without --gather: pixel = the direct light sampled on the "
                     "emitters at every pixel over the Gouraud-shaded indirect light; patch = "
                     "Gouraud-shaded B (also what watch's snapshots, an adaptive or "
                     "hierarchical solve and a result from an older server draw)")
          ->check(CLI::IsMember({"pixel", "patch"}))
          ->capture_default_str(),
      app.add_option("--pixel-samples", f.pixel_samples,
                     "--direct-light pixel: points per pixel, one light sample each")
          ->check(CLI::Range(1, 4096))
          ->capture_default_str(),
      app.add_option("--lightmap", f.lightmap,
                     "with --out FILE.glb: bake B into a SIZE x SIZE lightmap on a second UV set "
                     "(emissive texture, KHR_materials_emissive_strength; 0 = vertex colours)")
          ->capture_default_str(),
  };
  for (CLI::Option* option : added) option->group(kOutputGroup);
}

std::vector<std::string> GivenOutputFlags(const CLI::App& app) {
  std::vector<std::string> given;
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_group() == kOutputGroup && option->count() > 0) {
      given.push_back(option->get_name());
    }
  }
  return given;
}

absl::Status ValidateOutputFlags(const OutputFlags& f) {
  for (const absl::Status& s : {RequireExtension(f.out, "--out", {".ply", ".glb"}),
                                RequireExtension(f.render, "--render", {".png", ".pfm"}),
                                RequireExtension(f.report, "--report", {".json"}),
                                RequireExtension(f.patch_values, "--patch-values", {".csv"})}) {
    if (!s.ok()) return s;
  }
  const auto [w, h] = ParseSize(f.size);
  if (w <= 0 || h <= 0 || w > 16384 || h > 16384) {
    return absl::InvalidArgumentError(
        absl::StrCat("--size '", f.size, "': expected WxH with 1..16384 pixels each"));
  }
  if (!(f.metres_per_unit > 0)) return absl::InvalidArgumentError("--metres-per-unit must be > 0");
  if (f.lightmap != 0 && !absl::EndsWith(f.out, ".glb")) {
    return absl::InvalidArgumentError("--lightmap needs --out FILE.glb");
  }
  if (f.lightmap != 0 && (f.lightmap < 16 || f.lightmap > 16384)) {
    return absl::InvalidArgumentError(
        absl::StrCat("--lightmap ", f.lightmap, ": must be in [16, 16384] texels"));
  }
  if (f.gather < 0 || f.gather > 4096) {
    return absl::InvalidArgumentError(
        absl::StrCat("--gather ", f.gather, ": must be in [0, 4096]"));
  }
  return absl::OkStatus();
}

absl::StatusOr<Camera> CameraFromFlags(const OutputFlags& f, const PatchMesh& mesh,
                                       const RayCaster& caster, std::span<const Rgb> radiosity,
                                       const Vec3& origin) {
  Camera camera;
  std::tie(camera.width, camera.height) = ParseSize(f.size);
  camera.vertical_fov_degrees = f.fov_deg;
  const Vec3 up = f.camera_up.empty() ? Vec3{} : ToVec3(f.camera_up);
  if (f.camera_pos.empty()) {
    camera = DefaultCamera(mesh, caster, radiosity, camera, up);
  } else {
    camera.up = f.camera_up.empty() ? Vec3{0, 1, 0} : up;
    Vec3 lo = mesh.positions.at(0), hi = lo;
    for (const Vec3& p : mesh.positions) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    camera.position = ToVec3(f.camera_pos) - origin;
    camera.look_at = (lo + hi) * 0.5;
  }
  if (!f.camera_look_at.empty()) camera.look_at = ToVec3(f.camera_look_at) - origin;
  if (absl::Status s = ValidateCamera(camera); !s.ok()) return s;
  return camera;
}

absl::Status WriteOutputs(const OutputFlags& f, const Scene& scene, const PatchMesh& solved_mesh,
                          const std::vector<Rgb>& radiosity, const std::vector<Rgb>& indirect,
                          uint64_t seed, int threads, OutputTimings* timings) {
  // The mesh in the file's coordinates (a copy only for a recentred scene).
  std::optional<PatchMesh> translated;
  if (!(scene.origin == Vec3{})) translated = TranslatedMesh(solved_mesh, scene.origin);
  const PatchMesh& mesh = translated ? *translated : solved_mesh;
  std::vector<Rgb> radiance(radiosity.size());
  for (size_t p = 0; p < radiosity.size(); ++p) {
    for (int b = 0; b < kBands; ++b) radiance[p][b] = radiosity[p][b] / M_PI;
  }
  ToneMapOptions tone;
  tone.scale = AutoExposureScale(radiance);
  tone.exposure_stops = f.exposure;
  tone.srgb = !f.linear_png;
  if (f.out.empty() && f.render.empty()) return WriteValues(f, scene, mesh, radiosity);
  absl::StatusOr<ShadingMesh> shading = BuildShadingMesh(solved_mesh, FaceMaterials(scene));
  if (!shading.ok()) return shading.status();
  if (absl::EndsWith(f.out, ".ply")) {
    if (absl::Status s = WritePly(f.out, mesh, *shading, radiosity, tone); !s.ok()) return s;
  } else if (absl::EndsWith(f.out, ".glb")) {
    GltfOptions gltf;
    gltf.metres_per_unit = f.metres_per_unit;
    gltf.tone = tone;
    absl::Status s = f.lightmap > 0
                         ? WriteLightmapGlb(f.out, mesh, *shading, radiosity, f.lightmap, gltf)
                         : WriteGlb(f.out, mesh, *shading, radiosity, gltf);
    if (!s.ok()) return s;
  }
  if (!f.render.empty()) {
    if (absl::Status s = WriteRender(f, scene, solved_mesh, *shading, radiosity, indirect, tone,
                                     seed, threads, timings);
        !s.ok()) {
      return s;
    }
  }
  return WriteValues(f, scene, mesh, radiosity);
}

}  // namespace radflux::cli
