// What the picture tests share: a scene meshed for shading and ray casting (the patches, their
// attributes, the welded shading mesh and an Embree caster that reports u,v), and a camera
// inside the unit cube of testing::FurnaceCube.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <utility>

#include "solver/mesh/patch_attributes.h"
#include "solver/mesh/subdivide.h"
#include "solver/output/camera.h"
#include "solver/output/shading_mesh.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/scene/scene.h"

namespace radflux::testing {

struct MeshedScene {
  Scene scene;
  PatchMesh mesh;
  PatchAttributes attributes;
  ShadingMesh shading;
  std::unique_ptr<EmbreeRayCaster> caster;

  MeshedScene(Scene s, int64_t patches) : scene(std::move(s)) {
    MeshOptions options;
    options.target_patches = patches;
    mesh = *SubdivideScene(scene, options);
    attributes = ComputePatchAttributes(scene, mesh);
    shading = *BuildShadingMesh(mesh, FaceMaterials(scene));
    caster = *EmbreeRayCaster::Create(mesh);
  }
};

// From near the cube's z = 0 face towards z = 1, 80 degrees, 32 x 32 pixels.
inline Camera InsideUnitCube() {
  Camera camera;
  camera.position = {0.5, 0.5, 0.05};
  camera.look_at = {0.5, 0.5, 1};
  camera.vertical_fov_degrees = 80;
  camera.width = camera.height = 32;
  return camera;
}

}  // namespace radflux::testing
