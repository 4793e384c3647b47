// The output flags shared by `radflux solve` and `radflux result`: lit mesh, picture,
// camera, report and per-patch values; and writing them from a solved job.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/output/camera.h"
#include "solver/scene/scene.h"

namespace radflux::cli {

struct OutputFlags {
  std::string out;           // .ply or .glb
  std::string render;        // .png or .pfm
  std::string report;        // .json
  std::string patch_values;  // .csv
  std::vector<double> camera_pos, camera_look_at, camera_up;
  double fov_deg = 39.3077;
  std::string size = "512x512";
  double exposure = 0;                 // stops
  bool linear_png = false;             // PNG without the sRGB curve
  double metres_per_unit = 0.001;      // for .glb (the Cornell box is in millimetres)
  int gather = 0;                      // final-gather rays per pixel for --render (0: none)
  std::string direct_light = "pixel";  // --render without --gather: "pixel" samples the direct
                                       // light per pixel over the Gouraud-shaded indirect light,
                                       // "patch" Gouraud-shades B
  int pixel_samples = 4;  // points per pixel of --direct-light pixel, one light sample each
  int lightmap = 0;       // --out .glb with a SIZE x SIZE lightmap (0: vertex colours)
};

// Adds the output flags to `app`, in its help group kOutputGroup.
void AddOutputFlags(CLI::App& app, OutputFlags& flags);
inline constexpr const char* kOutputGroup = "Outputs";

// The output flags given on `app`'s command line, by their long name (empty: none).
std::vector<std::string> GivenOutputFlags(const CLI::App& app);

// Whether the picture asked for samples the direct light per pixel over the indirect part
// (JobResult::indirect): --render without --gather, --direct-light pixel.
bool DrawsDirectPerPixel(const OutputFlags& flags);

// Checks file extensions and camera values before any work starts.
absl::Status ValidateOutputFlags(const OutputFlags& flags);

// The camera from the flags; without --camera-pos, the default view's rule places it
// (solver/output/default_view.h: from inside for an enclosed scene, with `caster` probing
// `mesh` lit by `radiosity` (B per patch), and choosing up unless --camera-up is given; with
// --camera-pos, up is +y unless given); --camera-look-at wins over the rule's. The flags are in the
// file's coordinates; the camera is in the mesh's, which are the file's minus `origin`
// (Scene::origin of a recentred scene).
absl::StatusOr<Camera> CameraFromFlags(const OutputFlags& flags, const PatchMesh& mesh,
                                       const RayCaster& caster, std::span<const Rgb> radiosity,
                                       const Vec3& origin = {});

// Seconds spent in parts of WriteOutputs, for the job report.
struct OutputTimings {
  double gather = 0;  // the final gather of --render --gather N (0 without it)
};

// Writes the mesh, picture and per-patch values that were asked for (not the report), in
// the file's coordinates (scene.origin added back to the mesh's positions); fills `timings`
// when given. `indirect` is B's part that did not come straight from an emitter, per patch
// (JobResult::indirect); empty when not known, and the picture then Gouraud-shades B. A
// sampled picture (--gather, --direct-light pixel) seeds its pixels from `seed`, the job's.
absl::Status WriteOutputs(const OutputFlags& flags, const Scene& scene, const PatchMesh& mesh,
                          const std::vector<Rgb>& radiosity, const std::vector<Rgb>& indirect,
                          uint64_t seed, int threads, OutputTimings* timings = nullptr);

}  // namespace radflux::cli
