// Byte encodings of what the job store keeps per job: form-factor row blocks (with the
// statistics of their build) and solver checkpoints. Little-endian, exact (floats and
// doubles are stored bit for bit), so a resumed job computes exactly what it would have.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/bands.h"
#include "solver/formfactor/row_builder.h"
#include "solver/sparse/csr_matrix.h"

namespace radflux {

// A row block as built, with the statistics BuildRowBlock returned for it.
struct StoredRowBlock {
  RowBlock block;
  RowBlockStats stats;
  // A view-factor job's block (SurfaceRowPlan::BuildBlock's values of its rows, bit for
  // bit): `block` then has only first_row and row_count empty rows, and stats are unset.
  bool view_factors = false;
  std::vector<double> values;
};

std::string EncodeRowBlock(const StoredRowBlock& stored);
// DATA_LOSS when the bytes are not a row block.
absl::StatusOr<StoredRowBlock> DecodeRowBlock(std::string_view bytes);

// Several row blocks in one encoding (one file per checkpoint), in the given order.
std::string EncodeRowBlockGroup(const std::vector<const StoredRowBlock*>& blocks);
// DATA_LOSS when the bytes are not a row block group or one of its blocks is not a block.
absl::StatusOr<std::vector<StoredRowBlock>> DecodeRowBlockGroup(std::string_view bytes);

// The solver's state after `iteration` iterations: B per patch per band, and for
// southwell the unshot radiosity with it (empty for the other methods). `method` is the
// SolverMethod that wrote it (as int; -1 in checkpoints of the first format).
struct SolverCheckpoint {
  int iteration = 0;
  std::vector<Rgb> radiosity;
  int32_t method = -1;
  std::vector<Rgb> unshot;
};

std::string EncodeCheckpoint(const SolverCheckpoint& checkpoint);
absl::StatusOr<SolverCheckpoint> DecodeCheckpoint(std::string_view bytes);

}  // namespace radflux
