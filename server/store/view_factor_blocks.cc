#include "server/store/view_factor_blocks.h"

#include <cstring>
#include <filesystem>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "server/store/blob_file.h"

namespace radflux {
namespace {

constexpr absl::string_view kPrefix = "vf_block.";
constexpr absl::string_view kSuffix = ".rfb";
constexpr uint64_t kMagic = 0x31424656'58464c52;  // "RLFXVFB1"

std::string BlockPath(const std::string& dir, uint64_t first) {
  return absl::StrCat(dir, "/", kPrefix, first, kSuffix);
}

// Little-endian words: magic, surfaces, reciprocal, first, count, value count, then values.
std::string Encode(const ViewFactorBlock& b) {
  const uint64_t header[] = {kMagic, b.surfaces, b.reciprocal ? 1u : 0u, b.first, b.count,
                             b.values.size()};
  std::string bytes(sizeof(header) + b.values.size() * sizeof(double), '\0');
  std::memcpy(bytes.data(), header, sizeof(header));
  std::memcpy(bytes.data() + sizeof(header), b.values.data(), b.values.size() * sizeof(double));
  return bytes;
}

absl::StatusOr<ViewFactorBlock> Decode(const std::string& bytes, const std::string& path) {
  uint64_t header[6];
  if (bytes.size() < sizeof(header)) return absl::DataLossError(path + ": truncated block");
  std::memcpy(header, bytes.data(), sizeof(header));
  if (header[0] != kMagic || header[2] > 1 ||
      bytes.size() - sizeof(header) != header[5] * sizeof(double)) {
    return absl::DataLossError(path + ": not a view-factor block");
  }
  ViewFactorBlock b{header[1], header[2] == 1, header[3], header[4], {}};
  b.values.resize(header[5]);
  std::memcpy(b.values.data(), bytes.data() + sizeof(header), header[5] * sizeof(double));
  return b;
}

}  // namespace

absl::Status PutViewFactorBlock(const std::string& dir, const ViewFactorBlock& block) {
  return WriteBlobFile(BlockPath(dir, block.first), Encode(block), "view-factor rows");
}

absl::StatusOr<ViewFactorBlock> GetViewFactorBlock(const std::string& dir, uint64_t first) {
  const std::string path = BlockPath(dir, first);
  absl::StatusOr<std::string> bytes = ReadBlobFile(path);
  if (!bytes.ok()) return bytes.status();
  absl::StatusOr<ViewFactorBlock> block = Decode(*bytes, path);
  if (block.ok() && block->first != first) return absl::DataLossError(path + ": another block's rows");
  return block;
}

std::vector<uint64_t> StoredViewFactorBlocks(const std::string& dir) {
  std::vector<uint64_t> firsts;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string file = entry.path().filename().string();
    absl::string_view name = file;
    uint64_t first = 0;
    if (absl::ConsumePrefix(&name, kPrefix) && absl::ConsumeSuffix(&name, kSuffix) &&
        absl::SimpleAtoi(name, &first)) {
      firsts.push_back(first);
    }
  }
  return firsts;
}

}  // namespace radflux
