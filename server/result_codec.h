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

// EncodeResultChunks(MakeResultChunks(mesh, solve, report)) in two steps, byte for byte:
// everything that does not depend on B (the header, the vertex chunks, each patch chunk's
// vertices and source faces, and every length, B's being known from the patch count) is
// encoded from the mesh, e.g. while the job's rows are built; Finish adds B and the report
// after the solve, which then costs a copy of B and the report's encoding.
class ResultEncoder {
 public:
  explicit ResultEncoder(const PatchMesh& mesh);
  // The result's bytes; `solve.radiosity` has one value per patch of the mesh.
  std::string Finish(const SolveResult& solve, const std::string& report_json) const;

 private:
  size_t patch_count_ = 0;
  // before_b_[k]: the bytes from the end of patch chunk k - 1's B (the start, for k = 0) to
  // the start of patch chunk k's B.
  std::vector<std::string> before_b_;
};
absl::StatusOr<std::vector<v1::ResultChunk>> DecodeResultChunks(const std::string& bytes);

}  // namespace radflux
