// The wire form of a row block between a worker and the server: the job store's encoding
// (stored_codec.h) compressed with zstd, with the SHA-256 of the uncompressed bytes.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "radflux/v1/worker.pb.h"
#include "server/store/stored_codec.h"

namespace radflux {

// Fills result.rows_zstd and result.sha256 from `rows`.
void PackRowBlock(const StoredRowBlock& rows, v1::BlockResult& result);

// The rows of a result: DATA_LOSS when the bytes do not decompress, do not match their
// checksum or are not a row block.
absl::StatusOr<StoredRowBlock> UnpackRowBlock(const v1::BlockResult& result);

}  // namespace radflux
