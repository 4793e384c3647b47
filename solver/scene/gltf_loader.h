// glTF 2.0 loading (.gltf with its .bin buffers, and .glb) through tinygltf: every mesh
// primitive drawn as triangles, strips or fans under the default scene's node hierarchy,
// in scene space (node transforms composed down the tree; a mirroring transform keeps the
// faces' fronts by reversing their winding). Faces are triangles, counter-clockwise seen
// from the front, one object per node (its name, else its mesh's, else "node <i>") and one
// group per mesh primitive (the mesh's name, else "mesh <i>"; " primitive <k>" added when
// the mesh has several). Each node's vertices are its POSITION accessors' elements in
// scene space, once per accessor however many of its primitives share one, in the order
// first used. Materials: see gltf_material.h; textures: gltf_textures.h. Point and line primitives, and
// triangles with a repeated vertex, are left out and counted in Scene::import_log. Faces
// have no source line: messages name the mesh and primitive instead. The result is not yet
// validated: see ValidateScene.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/import_options.h"
#include "solver/scene/scene.h"

namespace radflux {

// At most this many triangles (all node instances together) are loaded; a larger scene is
// refused before it exhausts memory.
inline constexpr uint64_t kMaxGltfTriangles = uint64_t{1} << 24;

// Loads `path` (.gltf or .glb, told apart by the GLB header, not the name). Buffers and
// images named by relative URI are read from beside it (an image also when its name
// differs only in letter case). Errors are one line naming `path`
// (and the mesh and primitive when the problem is in one). With options.strict, a triangle
// with a repeated vertex is refused instead of dropped.
absl::StatusOr<Scene> LoadGltfFile(const std::string& path, const ImportOptions& options);

// The same from the bytes of a .gltf or .glb file (uploads, fuzzing), with the files it
// names (buffers, images) taken from `files`, keyed by the URI's path relative to the glTF
// file ("scene.bin", "textures/wall.png"; a path with ".." is never served; an image is
// also found ignoring letter case). A buffer in a
// file that is not there is an error. `name` is used in messages and as Scene::source.
absl::StatusOr<Scene> LoadGltfData(const std::string& data, const std::string& name,
                                   const ImportOptions& options,
                                   const std::map<std::string, std::string>& files = {});

}  // namespace radflux
