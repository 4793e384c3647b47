// RunStoredViewFactorJob: a view-factor job (v1::SolveOptions.viewfactors) as the server
// runs it: the stored model read as `radflux viewfactors` reads the file
// (wire/view_factor_convert.h), RunViewFactorJob (solver/formfactor/view_factor_job.h)
// writing the job's files into its directory, progress per block of surface rows, and a
// result whose ViewFactorFileChunks are those files' bytes: what `radflux viewfactors`
// writes for the same model and options, byte for byte.
#pragma once

#include "absl/status/statusor.h"
#include "radflux/v1/job.pb.h"
#include "server/jobs/job_runner.h"
#include "server/store/result_codec.h"
#include "wire/view_factor_convert.h"

namespace radflux {

// A view-factor job's model and the options it runs with, as admission and the run see them.
struct ViewFactorRun {
  ViewFactorScene model;
  std::string model_name;  // the model's file name (a bundle's main file)
  ViewFactorJobOptions options;  // integration resolved; output paths not set
  size_t surfaces = 0;     // rows of the matrix
};

// The stored model read as `radflux viewfactors` reads the file and validated, the request's
// options with the integration resolved and the options checked as that command checks its
// flags: INVALID_ARGUMENT naming the file or the option.
absl::StatusOr<ViewFactorRun> PrepareViewFactorRun(const v1::SolveOptions& request,
                                                   StoredScene stored);

// Bytes of disk the job may write at most: its checkpointed rows, its two files, its result.
uint64_t ViewFactorDiskBound(const ViewFactorRun& run);

// Runs the view-factor job to completion; CANCELLED when *context.stop was set. A job whose
// rows sum above 1 beyond their allowance succeeds with energy_balance_ok false and the
// message of `radflux viewfactors` (clients exit 4, as it does).
absl::StatusOr<EncodedResult> RunStoredViewFactorJob(const v1::Job& job, const RunContext& context);

}  // namespace radflux
