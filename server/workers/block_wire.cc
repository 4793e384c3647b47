#include "server/workers/block_wire.h"

#include <openssl/sha.h>
#include <zstd.h>

namespace radflux {
namespace {

constexpr unsigned long long kMaxRawBytes = 1ull << 31;  // a block larger than 2 GiB is refused

std::string Sha256(const std::string& data) {
  std::string digest(SHA256_DIGEST_LENGTH, '\0');
  SHA256(reinterpret_cast<const unsigned char*>(data.data()), data.size(),
         reinterpret_cast<unsigned char*>(digest.data()));
  return digest;
}

}  // namespace

void PackRowBlock(const StoredRowBlock& rows, v1::BlockResult& result) {
  const std::string raw = EncodeRowBlock(rows);
  std::string packed(ZSTD_compressBound(raw.size()), '\0');
  const size_t size = ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), 1);
  packed.resize(ZSTD_isError(size) ? 0 : size);
  result.set_rows_zstd(std::move(packed));
  result.set_sha256(Sha256(raw));
}

absl::StatusOr<StoredRowBlock> UnpackRowBlock(const v1::BlockResult& result) {
  const std::string& packed = result.rows_zstd();
  const unsigned long long raw_size = ZSTD_getFrameContentSize(packed.data(), packed.size());
  if (raw_size == ZSTD_CONTENTSIZE_ERROR || raw_size == ZSTD_CONTENTSIZE_UNKNOWN ||
      raw_size > kMaxRawBytes) {
    return absl::DataLossError("rows are not a zstd frame of a known size");
  }
  std::string raw(raw_size, '\0');
  const size_t got = ZSTD_decompress(raw.data(), raw.size(), packed.data(), packed.size());
  if (ZSTD_isError(got) || got != raw_size) return absl::DataLossError("rows do not decompress");
  if (Sha256(raw) != result.sha256()) return absl::DataLossError("bad checksum (SHA-256)");
  return DecodeRowBlock(raw);
}

}  // namespace radflux
