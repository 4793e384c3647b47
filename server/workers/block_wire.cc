#include "server/workers/block_wire.h"

#include <openssl/sha.h>
#include <zstd.h>

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

std::string Sha256(const std::string& data) {
  std::string digest(SHA256_DIGEST_LENGTH, '\0');
  SHA256(reinterpret_cast<const unsigned char*>(data.data()), data.size(),
         reinterpret_cast<unsigned char*>(digest.data()));
  return digest;
}

}  // namespace

v1::BlockResult PackRowBlock(const v1::BlockLease& lease, const StoredRowBlock& rows) {
  v1::BlockResult result;
  result.set_lease_id(lease.lease_id());
  result.set_job_id(lease.job_id());
  result.set_block_index(lease.block_index());
  result.set_first_row(lease.first_row());
  result.set_row_count(lease.row_count());
  const std::string raw = EncodeRowBlock(rows);
  std::string packed(ZSTD_compressBound(raw.size()), '\0');
  const size_t size = ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), 1);
  packed.resize(ZSTD_isError(size) ? 0 : size);
  result.set_rows_zstd(std::move(packed));
  result.set_sha256(Sha256(raw));
  return result;
}

uint64_t MaxRowBlockBytes(uint32_t rows, uint32_t patch_count) {
  // EncodeRowBlock: tag, first row, three sized vectors (offsets, columns, values), stats.
  constexpr uint64_t kFixed = 4 + 4 + 3 * 8 + 3 * 8;
  constexpr uint64_t kEntryBytes = sizeof(uint32_t) + sizeof(float);
  const uint64_t entries = uint64_t{rows} * patch_count;  // < 2^64: no overflow
  if (entries > kMaxRowBlockBytes / kEntryBytes) return kMaxRowBlockBytes;
  const uint64_t bytes = kFixed + (uint64_t{rows} + 1) * sizeof(uint64_t) + entries * kEntryBytes;
  return std::min(bytes, kMaxRowBlockBytes);
}

absl::StatusOr<StoredRowBlock> UnpackRowBlock(const v1::BlockResult& result,
                                              uint64_t max_raw_bytes) {
  const std::string& packed = result.rows_zstd();
  const unsigned long long raw_size = ZSTD_getFrameContentSize(packed.data(), packed.size());
  if (raw_size == ZSTD_CONTENTSIZE_ERROR || raw_size == ZSTD_CONTENTSIZE_UNKNOWN) {
    return absl::DataLossError("rows are not a zstd frame of a known size");
  }
  if (raw_size > max_raw_bytes) {
    return absl::DataLossError(absl::StrCat("rows declare ", raw_size,
                                            " bytes uncompressed, more than the ", max_raw_bytes,
                                            " bytes a block of this lease can take"));
  }
  std::string raw(raw_size, '\0');
  const size_t got = ZSTD_decompress(raw.data(), raw.size(), packed.data(), packed.size());
  if (ZSTD_isError(got) || got != raw_size) return absl::DataLossError("rows do not decompress");
  if (Sha256(raw) != result.sha256()) return absl::DataLossError("bad checksum (SHA-256)");
  return DecodeRowBlock(raw);
}

}  // namespace radflux
