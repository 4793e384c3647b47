// STL (binary and ASCII) into a radflux Scene, for view factors of CFD and urban meshes
// (uDALES's geometry format). Every facet becomes one triangle face, in file order, with the
// winding the file gives (its front side is counter-clockwise, as STL states); the stored
// facet normal is not used. Every facet is its own surface (object and group "facet<N>",
// N 1-based in file order) unless a groups side file names them.
//
// Groups side file: `<model path>.groups` (e.g. city.stl.groups) beside the model, read when
// it exists. One group name per facet, one per line, in facet order; blank lines and lines
// starting with '#' are skipped; a name is the whole line with surrounding blanks removed.
// Facets with the same name form one surface (object and group of that name). The number of
// names must equal the number of facets.
//
// Binary or ASCII: a file whose size is exactly 84 + 50 * (the 32-bit count at byte 80) is
// binary (even when it starts with "solid", as many exporters write); otherwise it must be
// ASCII and start with "solid". ASCII files may hold several solids one after the other.
// Every face uses the one material "stl" (black: reflectance 0, no emission).
//
// Errors: INVALID_ARGUMENT with one line "file:line: what is wrong" (binary: "file: facet N:
// ..."). The result is not yet validated: see ValidateScene.
#pragma once

#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "solver/scene/scene.h"

namespace radflux {

// The scene in the STL file `path`, grouped by `path`.groups when that file exists.
absl::StatusOr<Scene> LoadStlFile(const std::string& path);

// The scene in STL `bytes` (binary or ASCII), named `name` in messages; `groups` is the text
// of a groups side file (named `name`.groups in messages), or nullopt for one surface per
// facet.
absl::StatusOr<Scene> LoadStlBytes(const std::string& bytes, const std::string& name,
                                   const std::optional<std::string>& groups);

}  // namespace radflux
