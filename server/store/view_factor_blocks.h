// A view-factor job's checkpoints: its blocks of rows (SurfaceRowPlan's values, bit for bit)
// as blob files in the job's directory, one per block (vf_block.<first row>.rfb), each
// written atomically and durably as it is built, so that a job resumed after kill -9 builds
// only the blocks it had not stored (and computes exactly what an uninterrupted run does).
// A block records the plan it belongs to (surface count, reciprocal or not); one that does
// not match the resumed job's plan, or fails its check, is built again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace radflux {

struct ViewFactorBlock {
  uint64_t surfaces = 0;    // the plan's radiating surfaces
  bool reciprocal = false;  // the plan's kind of rows (SurfaceRowPlan::reciprocal)
  uint64_t first = 0, count = 0;  // rows [first, first + count)
  std::vector<double> values;     // SurfaceRowPlan::BuildBlock's values of those rows
};

// Stores `block` in `dir` (replacing one with the same first row); errors say what and where
// (a full disk: RESOURCE_EXHAUSTED "disk full writing ...").
absl::Status PutViewFactorBlock(const std::string& dir, const ViewFactorBlock& block);

// The block of `dir` starting at row `first`: NOT_FOUND when absent, DATA_LOSS when its file
// fails its check or does not decode.
absl::StatusOr<ViewFactorBlock> GetViewFactorBlock(const std::string& dir, uint64_t first);

// The first rows of the blocks stored in `dir` (their files' names; not read).
std::vector<uint64_t> StoredViewFactorBlocks(const std::string& dir);

}  // namespace radflux
