// Scene: the diffuse surfaces a job is asked about, as loaded from a file.
// Faces are planar convex polygons with outward (lit-side) normals by their winding
// (counter-clockwise seen from the front). A validated scene has no NaN, no degenerate
// or non-planar face, reflectance in [0,1), non-negative emission and at least one emitter.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/core/bands.h"
#include "solver/core/vec3.h"
#include "solver/scene/import_log.h"

namespace radflux {

struct Material {
  std::string name;
  Rgb reflectance{};       // diffuse reflectance rho per band, in [0, 1)
  Rgb emission{};          // emitted radiosity E = pi * L_e, W/m^2 per band
  bool two_sided = false;  // each face is two back-to-back patches, each lit from its side
  // Opaque fraction of each face's area, in (0, 1] (alpha cut-outs, face_textures.h): a ray
  // meeting the face passes through with probability 1 - opacity, and the face reflects and
  // emits from its opaque part only (its power is opacity * area * B).
  double opacity = 1;

  bool IsEmitter() const { return MaxComponent(emission) > 0; }
};

struct Face {
  std::vector<uint32_t> vertices;  // indices into Scene::positions, counter-clockwise
  uint32_t material = 0;           // index into Scene::materials
  uint32_t object = 0;             // index into Scene::objects ('o' name)
  uint32_t group = 0;              // index into Scene::groups ('g' name)
  int source_line = 0;             // 1-based line in the source file, 0 if unknown
  uint32_t source_file = 0;        // index into Scene::files (0: the main file, Scene::source)
  bool obstruction = false;        // blocks light but has no view factors (View3D 'O' surface)
  bool back_face = false;          // the back-face twin of a two-sided face (two_sided.h)
};

struct Scene {
  std::string source;  // file name the scene came from, for messages
  // Files the faces came from (includes, buffers), for messages; files[0] == source when
  // non-empty. Empty: every face is from `source`.
  std::vector<std::string> files;
  std::vector<Vec3> positions;
  std::vector<Face> faces;
  std::vector<Material> materials;
  std::vector<std::string> objects;
  std::vector<std::string> groups;
  ImportLog import_log;  // what import fixed or left out, one entry per kind
  // The file's coordinates are positions + origin (scene units): import recentres a scene
  // far from the origin (recentre.h) and outputs add this back. Zero for most scenes.
  Vec3 origin;

  // "file:line" of face f (the file alone when the line is unknown).
  std::string FaceLocation(size_t f) const;

  // "file:line (object 'o', face k)" for messages about face f.
  std::string DescribeFace(size_t f) const;
};

// The index of `name` in `names`, appending it when new (`index` maps names to indices):
// how loaders number the objects and groups of a scene in the order they first appear.
uint32_t InternName(std::vector<std::string>& names, std::map<std::string, uint32_t>& index,
                    const std::string& name);

// Newell normal of a polygon (unnormalised; length = 2 * area for a planar polygon).
Vec3 PolygonNewellNormal(const std::vector<Vec3>& polygon);
std::vector<Vec3> FacePolygon(const Scene& scene, const Face& face);
// FacePolygon written into `polygon`, reusing its storage (no allocation in a loop).
void FacePolygonInto(const Scene& scene, const Face& face, std::vector<Vec3>& polygon);

}  // namespace radflux
