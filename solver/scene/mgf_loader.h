// MGF (Materials and Geometry Format, Greg Ward 1995; the scene format of RenderPark and
// Radiance's mgf2rad) into a radflux Scene.
//
// Read: vertices (v, p, n), faces (f) and faces with holes (fh, joined into one contour),
// objects (o; nested names joined with '.', e.g. "casing.outer", as Scene::objects),
// colours and materials (see mgf_material.h), transforms (xf, with -a arrays, nested),
// includes (i, relative to the including file, with an optional transform) and the
// primitives sph, cyl, cone, ring, torus and prism (tessellated as mgf_primitives.h states,
// at ImportOptions::curve_segments). ies and ir are skipped, as are unknown entities: each
// kind is counted in Scene::import_log. Faces keep the order and winding MGF gives them (a
// transform that mirrors reverses them); the import rules triangulate what is not convex.
// Scene::files lists every file read (main first); Face::source_file/source_line give the
// statement each face came from.
//
// Errors: INVALID_ARGUMENT with one line "file:line: what is wrong". Include cycles,
// includes or objects (o) nested deeper than the limits below, and files that would execute
// more statements or make more faces than the limits (huge xf arrays) are refused.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/import_options.h"
#include "solver/scene/scene.h"

namespace radflux {

struct MgfLimits {
  uint64_t max_statements = 10'000'000;  // statements executed (each array element counts)
  uint64_t max_faces = 5'000'000;        // faces made, primitives' facets included
  int max_include_depth = 32;            // includes within includes
  size_t max_object_depth = 64;          // objects (o) open at once
  int max_curve_segments = 1024;         // largest ImportOptions::curve_segments accepted
};

// The text of an included file, given its path (already joined to the including file's
// folder and normalised, e.g. "scenes/Materials/dupont.mgf"), or an error saying why not.
using MgfFileReader = std::function<absl::StatusOr<std::string>(const std::string& path)>;

// The scene in the MGF file `path`; includes are read from disk.
absl::StatusOr<Scene> LoadMgfFile(const std::string& path, const ImportOptions& options);

// The scene in MGF `text`, named `name` in messages (and Scene::files[0]); includes are read
// through `reader`.
absl::StatusOr<Scene> LoadMgfText(const std::string& text, const std::string& name,
                                  const ImportOptions& options, const MgfFileReader& reader,
                                  const MgfLimits& limits = {});

// A reader serving the files in `files` (path -> text); other paths are NOT_FOUND.
MgfFileReader MgfReaderFromMap(std::map<std::string, std::string> files);

}  // namespace radflux
