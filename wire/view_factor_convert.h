// A view-factor job (v1::SolveOptions.viewfactors) and the solver's ViewFactorJobOptions: the
// request a client builds from `radflux viewfactors`' flags, the options the server runs it
// with, and which of those flags a request names (what CheckViewFactorFlags judges), and the
// model of a stored scene read as `radflux viewfactors` reads the file.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/job.pb.h"
#include "solver/formfactor/view_factor_job.h"
#include "solver/formfactor/view_factor_scene.h"
#include "wire/stored_scene.h"

namespace radflux {

// `full` (ToProto of the job and import options: every field set) with only the fields of
// the flags in `given` kept (the flag names of `radflux viewfactors`), and `viewfactors`
// set: so that the server knows which options were given, as the local command does.
v1::SolveOptions ViewFactorRequestOptions(v1::SolveOptions full, const v1::ViewFactorOptions& vf,
                                          std::span<const std::string> given);

// The flags whose fields `options` sets (solve, form-factor, import and adaptive ones).
std::vector<std::string> ViewFactorFlagsOf(const v1::SolveOptions& options);

// The job options of a view-factor request (output paths left empty, enclosure false: the
// model's .vs3 control record says). INVALID_ARGUMENT naming the flag of a bad value.
absl::StatusOr<ViewFactorJobOptions> ViewFactorJobOptionsFromProto(const v1::SolveOptions& p);

// The stored scene's model as LoadViewFactorScene reads its file (a bundle through
// LoadViewFactorBundle; the older upload forms through LoadStoredScene).
absl::StatusOr<ViewFactorScene> LoadStoredViewFactorScene(StoredScene scene,
                                                          const ImportOptions& import);

// The model's file name: a bundle's main file, else the stored name.
std::string StoredModelName(const StoredScene& scene);

}  // namespace radflux
