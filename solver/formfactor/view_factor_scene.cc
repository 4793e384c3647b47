#include "solver/formfactor/view_factor_scene.h"

#include <optional>
#include <set>

#include "absl/strings/match.h"
#include "solver/scene/stl_loader.h"
#include "solver/scene/vs3_loader.h"

namespace radflux {
namespace {

absl::StatusOr<ViewFactorScene> FromVs3(absl::StatusOr<Vs3Model> model, const std::string& name) {
  if (!model.ok()) return model.status();
  if (model->control.emittances) {
    return absl::InvalidArgumentError(
        name + ": C emit=1 asks for View3D's interchange factors with emissivities, which "
               "radflux does not compute; set emit=0 for view factors");
  }
  return ViewFactorScene{std::move(model->scene), model->control.enclosure};
}

absl::StatusOr<ViewFactorScene> FromScene(absl::StatusOr<Scene> scene) {
  if (!scene.ok()) return scene.status();
  return ViewFactorScene{*std::move(scene), false};
}

}  // namespace

size_t ViewFactorSurfaceCount(const Scene& scene, SurfaceGrouping by) {
  std::set<uint32_t> names;
  size_t faces = 0;
  for (const Face& face : scene.faces) {
    if (face.obstruction) continue;
    ++faces;
    names.insert(by == SurfaceGrouping::kGroup ? face.group : face.object);
  }
  return by == SurfaceGrouping::kFace ? faces : names.size();
}

bool IsRawViewFactorModel(const std::string& path) {
  return absl::EndsWithIgnoreCase(path, ".stl") || absl::EndsWithIgnoreCase(path, ".vs3");
}

absl::StatusOr<ViewFactorScene> LoadViewFactorScene(const std::string& path,
                                                    const ImportOptions& import) {
  if (absl::EndsWithIgnoreCase(path, ".stl")) return FromScene(LoadStlFile(path));
  if (absl::EndsWithIgnoreCase(path, ".vs3")) return FromVs3(LoadVs3File(path), path);
  return FromScene(LoadScene(path, import));
}

absl::StatusOr<ViewFactorScene> LoadViewFactorBundle(const SceneBundle& bundle,
                                                     const ImportOptions& import) {
  if (!IsRawViewFactorModel(bundle.main)) return FromScene(LoadSceneBundle(bundle, import));
  const auto main = bundle.files.find(bundle.main);
  if (main == bundle.files.end()) {
    return absl::InvalidArgumentError(bundle.main + ": not in the bundle");
  }
  if (absl::EndsWithIgnoreCase(bundle.main, ".vs3")) {
    return FromVs3(LoadVs3Text(main->second, bundle.main), bundle.main);
  }
  const auto groups = bundle.files.find(bundle.main + ".groups");
  return FromScene(LoadStlBytes(
      main->second, bundle.main,
      groups == bundle.files.end() ? std::nullopt : std::optional<std::string>(groups->second)));
}

}  // namespace radflux
