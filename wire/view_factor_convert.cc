#include "wire/view_factor_convert.h"

#include <algorithm>
#include <functional>

#include "absl/strings/str_cat.h"
#include "wire/proto_convert.h"

namespace radflux {
namespace {

// A flag and the request field it sets.
struct FieldFlag {
  const char* flag;
  std::function<bool(const v1::SolveOptions&)> has;
  std::function<void(v1::SolveOptions&)> clear;
};

#define RADFLUX_FIELD(flag, field)                                 \
  FieldFlag {                                                      \
    flag, [](const v1::SolveOptions& o) { return o.has_##field(); }, \
        [](v1::SolveOptions& o) { o.clear_##field(); }             \
  }
#define RADFLUX_IMPORT(flag, has_expr, clear_stmt)                                  \
  FieldFlag {                                                                       \
    flag, [](const v1::SolveOptions& o) { const auto& i = o.import_options(); return has_expr; }, \
        [](v1::SolveOptions& o) { auto& i = *o.mutable_import_options(); clear_stmt; }  \
  }
#define RADFLUX_ADAPTIVE(flag, field)                                                \
  FieldFlag {                                                                        \
    flag, [](const v1::SolveOptions& o) { return o.viewfactors().has_##field(); },   \
        [](v1::SolveOptions& o) { o.mutable_viewfactors()->clear_##field(); }        \
  }

const std::vector<FieldFlag>& FieldFlags() {
  static const std::vector<FieldFlag> flags = {
      RADFLUX_FIELD("--patches", target_patches),
      RADFLUX_FIELD("--max-edge", max_edge),
      RADFLUX_FIELD("--form-factors", form_factor_method),
      RADFLUX_FIELD("--rays", rays),
      RADFLUX_FIELD("--hemicube-res", hemicube_res),
      RADFLUX_FIELD("--samples", samples),
      RADFLUX_FIELD("--cutoff", cutoff),
      RADFLUX_FIELD("--seed", seed),
      RADFLUX_FIELD("--solver", solver),
      RADFLUX_FIELD("--tolerance", tolerance),
      RADFLUX_FIELD("--max-iterations", max_iterations),
      RADFLUX_IMPORT("--max-reflectance", i.has_max_reflectance(), i.clear_max_reflectance()),
      RADFLUX_IMPORT("--strict", i.strict(), i.clear_strict()),
      RADFLUX_IMPORT("--two-sided", i.two_sided(), i.clear_two_sided()),
      RADFLUX_IMPORT("--emit", i.emit_size() > 0, i.clear_emit()),
      RADFLUX_IMPORT("--curve-segments", i.has_curve_segments(), i.clear_curve_segments()),
      RADFLUX_ADAPTIVE("--vf-tolerance", vf_tolerance),
      RADFLUX_ADAPTIVE("--far-ratio", far_ratio),
      RADFLUX_ADAPTIVE("--middle-ratio", middle_ratio),
      RADFLUX_ADAPTIVE("--memory-limit", memory_limit),
  };
  return flags;
}

#undef RADFLUX_FIELD
#undef RADFLUX_IMPORT
#undef RADFLUX_ADAPTIVE

// OK when lo <= value <= hi, else INVALID_ARGUMENT naming `flag` (NaN is outside).
absl::Status CheckRange(const char* flag, double value, double lo, double hi) {
  if (value >= lo && value <= hi) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat(flag, " ", value, " is outside [", lo, ", ", hi, "]"));
}

absl::StatusOr<SurfaceGrouping> ParseBy(const v1::ViewFactorOptions& vf) {
  const std::string by = vf.has_by() ? vf.by() : "object";
  if (by == "object") return SurfaceGrouping::kObject;
  if (by == "group") return SurfaceGrouping::kGroup;
  if (by == "face") return SurfaceGrouping::kFace;
  return absl::InvalidArgumentError("--by '" + by + "': expected object, group or face");
}

absl::StatusOr<ViewFactorIntegration> ParseIntegration(const v1::ViewFactorOptions& vf) {
  const std::string name = vf.has_integration() ? vf.integration() : "auto";
  if (name == "auto") return ViewFactorIntegration::kAuto;
  if (name == "adaptive") return ViewFactorIntegration::kAdaptive;
  if (name == "patches") return ViewFactorIntegration::kPatches;
  return absl::InvalidArgumentError("--integration '" + name +
                                    "': expected auto, adaptive or patches");
}

// The adaptive knobs and the output's format and --min-vf into `o`.
absl::Status ReadViewFactorFields(const v1::ViewFactorOptions& vf, ViewFactorJobOptions& o) {
  const std::string format = vf.has_format() ? vf.format() : "csv";
  const std::optional<ViewFactorFormat> parsed = ParseViewFactorFormat(format);
  if (!parsed) {
    return absl::InvalidArgumentError("--format '" + format + "': expected csv, sparse or view3d");
  }
  o.output.format = *parsed;
  if (vf.has_min_vf()) o.output.min_vf = vf.min_vf();
  PairIntegration& pairs = o.surface_rows.integration;
  if (vf.has_vf_tolerance()) pairs.tolerance = vf.vf_tolerance();
  if (vf.has_far_ratio()) pairs.far_ratio = vf.far_ratio();
  if (vf.has_middle_ratio()) pairs.middle_ratio = vf.middle_ratio();
  if (vf.has_memory_limit()) o.surface_rows.memory_limit = vf.memory_limit();
  for (const absl::Status& s : {CheckRange("--min-vf", o.output.min_vf, 0, 1),
                                CheckRange("--vf-tolerance", pairs.tolerance, 1e-9, 1),
                                CheckRange("--far-ratio", pairs.far_ratio, 0, 1e9),
                                CheckRange("--middle-ratio", pairs.middle_ratio, 0, 1e9)}) {
    if (!s.ok()) return s;
  }
  return absl::OkStatus();
}

}  // namespace

v1::SolveOptions ViewFactorRequestOptions(v1::SolveOptions full, const v1::ViewFactorOptions& vf,
                                          std::span<const std::string> given) {
  *full.mutable_viewfactors() = vf;
  full.clear_block_size();  // not a flag: threads' work split, no value depends on it
  for (const FieldFlag& f : FieldFlags()) {
    if (std::find(given.begin(), given.end(), f.flag) == given.end()) f.clear(full);
  }
  return full;
}

std::vector<std::string> ViewFactorFlagsOf(const v1::SolveOptions& options) {
  std::vector<std::string> flags;
  for (const FieldFlag& f : FieldFlags()) {
    if (f.has(options)) flags.push_back(f.flag);
  }
  return flags;
}

absl::StatusOr<ViewFactorJobOptions> ViewFactorJobOptionsFromProto(const v1::SolveOptions& p) {
  ViewFactorJobOptions o;
  absl::StatusOr<JobOptions> job = FromProto(p);
  if (!job.ok()) return job.status();
  o.job = *std::move(job);
  absl::StatusOr<SurfaceGrouping> by = ParseBy(p.viewfactors());
  if (!by.ok()) return by.status();
  o.by = *by;
  absl::StatusOr<ViewFactorIntegration> integration = ParseIntegration(p.viewfactors());
  if (!integration.ok()) return integration.status();
  o.integration = *integration;
  if (absl::Status s = ReadViewFactorFields(p.viewfactors(), o); !s.ok()) return s;
  return o;
}

absl::StatusOr<ViewFactorScene> LoadStoredViewFactorScene(StoredScene scene,
                                                          const ImportOptions& import) {
  if (scene.files.empty()) {
    absl::StatusOr<Scene> loaded = LoadStoredScene(std::move(scene), import);
    if (!loaded.ok()) return loaded.status();
    return ViewFactorScene{*std::move(loaded), false};
  }
  return LoadViewFactorBundle(TakeSceneBundle(scene), import);
}

std::string StoredModelName(const StoredScene& scene) {
  return scene.files.empty() ? scene.name : scene.files[0].path;
}

}  // namespace radflux
