// A finished job's result as the list of ResultChunk messages GetResult streams (header
// job filled in when served), and its byte encoding for the job store.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/radiosity.pb.h"
#include "server/store/blob_file.h"
#include "solver/mesh/patch_mesh.h"
#include "solver/solve/solver.h"

namespace radflux {

// Patches and vertices per chunk: keeps every chunk far below gRPC's 4 MB message limit.
inline constexpr size_t kResultChunkItems = 16384;

// Header (without the job), vertex chunks, patch chunks with B exactly as solved and its
// indirect part (JobResult::indirect; left out when empty), report.
std::vector<v1::ResultChunk> MakeResultChunks(const PatchMesh& mesh, const SolveResult& solve,
                                              const std::vector<Rgb>& indirect,
                                              const std::string& report_json);

// Length-prefixed concatenation of the chunks' wire encodings.
std::string EncodeResultChunks(const std::vector<v1::ResultChunk>& chunks);
// The chunks back; with `header_and_report_only`, only the first (header) and the last
// (report), the others' lengths checked but not parsed.
absl::StatusOr<std::vector<v1::ResultChunk>> DecodeResultChunks(
    const std::string& bytes, bool header_and_report_only = false);

// A finished job's result: EncodeResultChunks' bytes, and the blob file storing them.
struct EncodedResult {
  std::string bytes;
  std::string file;  // BlobBuilder::File() of bytes (blob_file.h)
  // Whether the solve reached its tolerance; if not, the job's message ("not converged:
  // residual R after N iterations (tolerance T)"). Set by RunStoredJob.
  bool converged = true;
  // Whether the energy balance closed; if not, the message says so (after the not-converged
  // clause when both). Set by RunStoredJob.
  bool energy_balance_ok = true;
  std::string message;
};

// EncodeResultChunks(MakeResultChunks(mesh, solve, indirect, report)) and its blob file in two
// steps,
// the bytes exactly those: everything that does not depend on B (the header, the vertex
// chunks, each patch chunk's vertices and source faces, and every length, B's being known
// from the patch count) is encoded from the mesh, and what comes before the first patch's
// B also compressed and hashed for the blob, e.g. while the job's rows are built; Finish
// adds B, its indirect part and the report after the solve.
class ResultEncoder {
 public:
  explicit ResultEncoder(const PatchMesh& mesh);
  // `solve.radiosity` and `indirect` have one value per patch of the mesh (else
  // INVALID_ARGUMENT).
  absl::StatusOr<EncodedResult> Finish(const SolveResult& solve, const std::vector<Rgb>& indirect,
                                       const std::string& report_json) &&;

 private:
  size_t patch_count_ = 0;
  // before_b_[k]: the bytes from the end of patch chunk k - 1's B (the start, for k = 0) to
  // the start of patch chunk k's B.
  std::vector<std::string> before_b_;
  // before_i_[k]: the bytes from the end of patch chunk k's B to the start of its I.
  std::vector<std::string> before_i_;
  BlobBuilder blob_;  // before_b_[0] appended
  absl::Status status_;
};

}  // namespace radflux
