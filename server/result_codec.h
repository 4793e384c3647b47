// A finished job's result as the list of ResultChunk messages GetResult streams (header
// job filled in when served), and its byte encoding for the job store.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/radiosity.pb.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/solve/solver.h"

namespace radflux {

// Patches and vertices per chunk: keeps every chunk far below gRPC's 4 MB message limit.
inline constexpr size_t kResultChunkItems = 16384;

// Header (without the job), vertex chunks, patch chunks with B exactly as solved, report.
std::vector<v1::ResultChunk> MakeResultChunks(const PatchMesh& mesh, const SolveResult& solve,
                                              const std::string& report_json);

// Length-prefixed concatenation of the chunks' wire encodings.
std::string EncodeResultChunks(const std::vector<v1::ResultChunk>& chunks);
absl::StatusOr<std::vector<v1::ResultChunk>> DecodeResultChunks(const std::string& bytes);

}  // namespace radflux
