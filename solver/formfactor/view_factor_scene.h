// The model of a view-factor job read as `radflux viewfactors` reads it, from a file or from
// an uploaded bundle (the service), so that both compute on the same surfaces: STL and .vs3
// are read as they are, without the import rules (surface k of the output is facet or
// surface record k of the file, what uDALES and View3D users index by); other formats go
// through LoadScene / LoadSceneBundle with the import rules given.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "solver/formfactor/surface_view_factors.h"
#include "solver/scene/import_options.h"
#include "solver/scene/load_scene.h"
#include "solver/scene/scene.h"

namespace radflux {

struct ViewFactorScene {
  Scene scene;             // not yet validated (ValidateScene)
  bool enclosure = false;  // a .vs3 control record's encl=1: adjust for closure (View3D)
};

// True for the formats read without import rules (.stl, .vs3, any case).
bool IsRawViewFactorModel(const std::string& path);

// The model in `path`. INVALID_ARGUMENT naming the file for what its loader refuses, and for
// a .vs3 asking for emissivities (emit=1: interchange factors, which radflux does not compute).
absl::StatusOr<ViewFactorScene> LoadViewFactorScene(const std::string& path,
                                                    const ImportOptions& import);

// The same for a bundle whose main file is the model (an STL's groups side file is
// `main`.groups in the bundle); only the bundle's files are read.
absl::StatusOr<ViewFactorScene> LoadViewFactorBundle(const SceneBundle& bundle,
                                                     const ImportOptions& import);

// How many surfaces (by `by`) of `scene` radiate: the rows of its view-factor matrix.
size_t ViewFactorSurfaceCount(const Scene& scene, SurfaceGrouping by);

}  // namespace radflux
