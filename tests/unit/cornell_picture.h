// A scene (the Cornell box, or any loaded scene) solved at the CLI's defaults and rendered
// as `radflux solve --render` does (welded shading mesh, per-vertex radiosity, one ray per
// pixel): what the picture tests measure.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "solver/output/render.h"
#include "solver/output/shading_mesh.h"
#include "solver/output/vertex_radiosity.h"
#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "tests/source_path.h"

namespace radflux::testing {

// A solved scene (--patches 2000 as the CLI's default).
struct SolvedScene {
  std::unique_ptr<JobResult> result;  // result->job: scene, mesh and caster
  std::vector<Rgb> vertex_radiosity;  // per PatchMesh position, as the renderer takes it

  const PreparedJob& job() const { return *result->job; }
};

// `scene` solved (empty on failure, with a test failure).
inline SolvedScene SolveDefaults(absl::StatusOr<Scene> scene) {
  SolvedScene out;
  EXPECT_TRUE(scene.ok()) << scene.status();
  if (!scene.ok()) return out;
  const std::vector<uint32_t> materials = FaceMaterials(*scene);
  JobOptions options;
  options.mesh.target_patches = 2000;  // the CLI's default
  absl::StatusOr<JobResult> result = RunJob(*std::move(scene), options);
  EXPECT_TRUE(result.ok()) << result.status();
  if (!result.ok()) return out;
  out.result = std::make_unique<JobResult>(*std::move(result));
  const PatchMesh& mesh = out.job().mesh;
  absl::StatusOr<ShadingMesh> shading = BuildShadingMesh(mesh, materials);
  EXPECT_TRUE(shading.ok()) << shading.status();
  if (!shading.ok()) return out;
  absl::StatusOr<std::vector<Rgb>> vertex_b =
      VertexRadiosity(mesh, *shading, out.result->solve.radiosity);
  EXPECT_TRUE(vertex_b.ok()) << vertex_b.status();
  if (vertex_b.ok()) out.vertex_radiosity = *std::move(vertex_b);
  return out;
}

// scenes/cornell_box.obj solved.
inline SolvedScene SolveCornellDefaults() {
  return SolveDefaults(LoadObjFile(SourcePath("scenes/cornell_box.obj")));
}

// The solved scene's radiance picture through `camera` (empty on failure, with a test
// failure).
inline Image RenderSolved(const SolvedScene& solved, const Camera& camera) {
  absl::StatusOr<Image> image =
      RenderRadiance(solved.job().mesh, *solved.job().caster, solved.vertex_radiosity, camera, {});
  EXPECT_TRUE(image.ok()) << image.status();
  return image.ok() ? *std::move(image) : Image{};
}

// The share of `image`'s pixels with radiance > 0 in some band (0 for an empty image).
inline double LitShare(const Image& image) {
  int lit = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float* rgb = image.Pixel(x, y);
      lit += rgb[0] > 0 || rgb[1] > 0 || rgb[2] > 0;
    }
  }
  return image.width * image.height > 0 ? lit / double(image.width * image.height) : 0;
}

}  // namespace radflux::testing
