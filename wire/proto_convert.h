// The one place where radflux types meet their radflux.v1 protobuf messages and where
// absl::Status meets grpc::Status (the codes map one to one).
#pragma once

#include <grpcpp/support/status.h>

#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/job.pb.h"
#include "solver/core/bands.h"
#include "solver/pipeline.h"
#include "solver/scene/import_options.h"

namespace radflux {

// Solve options from their message: unset fields keep JobOptions' defaults; an unknown
// method or solver name is INVALID_ARGUMENT. Values are range-checked by ValidateJobOptions.
absl::StatusOr<JobOptions> FromProto(const v1::SolveOptions& proto);

// All solve options as a message (every field set), for clients submitting JobOptions.
v1::SolveOptions ToProto(const JobOptions& options);

// Import options from their message: unset fields keep ImportOptions' defaults. An --emit
// with no material name or a radiance that is negative or not finite is INVALID_ARGUMENT
// naming it; the other values are checked where they are used (ApplyImportRules, the MGF
// loader), with the same messages as for `radflux solve`.
absl::StatusOr<ImportOptions> FromProto(const v1::ImportOptions& proto);

// All import options as a message (every field set), for clients submitting them.
v1::ImportOptions ToProto(const ImportOptions& options);

grpc::Status ToGrpcStatus(const absl::Status& status);
absl::Status FromGrpcStatus(const grpc::Status& status);

// True for the states a job ends in: SUCCEEDED, FAILED, CANCELLED.
bool IsTerminal(v1::JobState state);

// B per patch as a snapshot message with the given bands (empty = all) and format.
v1::Snapshot ToProtoSnapshot(int iteration, const std::vector<Rgb>& radiosity,
                             const std::vector<int>& bands, v1::SnapshotFormat format);

// Values of a snapshot, patch-major over its bands (float16 widened); INVALID_ARGUMENT
// when the data size does not match.
absl::StatusOr<std::vector<float>> SnapshotValues(const v1::Snapshot& snapshot);

// IEEE binary16 conversions (round to nearest even; overflow to infinity).
uint16_t FloatToHalf(float value);
float HalfToFloat(uint16_t half);

}  // namespace radflux
