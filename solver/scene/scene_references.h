// The files a scene file names, which its loader reads beside it: what `radflux submit`
// sends with the scene as one bundle, so that the server loads what `radflux solve` loads.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace radflux {

// Every file that the scene file `path` names and that is on disk (found as FindFile finds
// it), `path` itself left out, each once, in the order first named:
//   .obj   its mtllib files, and their textures (map_Kd, map_Ke, map_d), relative to the OBJ;
//   .gltf, .glb   buffers and images named by a relative URI (data: URIs are inline);
//   .mgf   its includes, recursively (found by the MGF interpreter itself);
//   .stl   its groups side file (SCENE.stl.groups);
//   .vs3 and others   none.
// A named file that is not on disk is left out: the loader then says what is missing.
// NOT_FOUND when `path` cannot be read; an MGF file's includes that do not load give the
// MGF loader's error.
absl::StatusOr<std::vector<std::string>> SceneReferences(const std::string& path);

}  // namespace radflux
