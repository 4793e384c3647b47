// The wire form of a row block between a worker and the server: the job store's encoding
// (stored_codec.h) compressed with zstd, with the SHA-256 of the uncompressed bytes.
#pragma once

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "radflux/v1/worker.pb.h"
#include "server/store/stored_codec.h"

namespace radflux {

// The result answering `lease` (its lease, job, block and rows) with `rows` packed:
// rows_zstd and sha256 of the encoded block.
v1::BlockResult PackRowBlock(const v1::BlockLease& lease, const StoredRowBlock& rows);

// A hard cap on the uncompressed bytes of one row block from the wire (256 MiB).
inline constexpr uint64_t kMaxRowBlockBytes = uint64_t{256} << 20;

// The most bytes the encoding of `rows` rows over `patch_count` columns can take (every
// column in every row), or kMaxRowBlockBytes when that is less.
uint64_t MaxRowBlockBytes(uint32_t rows, uint32_t patch_count);

// The rows of a result: DATA_LOSS when its declared size is unknown or above
// `max_raw_bytes` (nothing is allocated then: a zstd bomb costs nothing), or the bytes do
// not decompress, do not match their checksum or are not a row block.
absl::StatusOr<StoredRowBlock> UnpackRowBlock(const v1::BlockResult& result,
                                              uint64_t max_raw_bytes);

}  // namespace radflux
