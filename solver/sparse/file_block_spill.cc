#include "solver/sparse/file_block_spill.h"

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

template <typename T>
absl::Status ReadArray(const SpillFile& file, std::vector<T>& v, size_t count, uint64_t& offset) {
  v.resize(count);
  const size_t bytes = count * sizeof(T);
  absl::Status s = file.Read(offset, v.data(), bytes);
  offset += bytes;
  return s;
}

}  // namespace

FileBlockSpill::FileBlockSpill(std::string directory) : file_(std::move(directory), "rows") {}

absl::Status FileBlockSpill::Write(const RowBlock& block) {
  absl::StatusOr<uint64_t> offset =
      file_.Append(block.row_begin.data(), block.row_begin.size() * sizeof(uint64_t));
  if (!offset.ok()) return offset.status();
  for (const auto& [data, bytes] :
       {std::pair<const void*, size_t>{block.col.data(), block.col.size() * sizeof(uint32_t)},
        {block.value.data(), block.value.size() * sizeof(float)}}) {
    if (absl::StatusOr<uint64_t> s = file_.Append(data, bytes); !s.ok()) return s.status();
  }
  extents_.push_back({*offset, block.first_row, block.RowCount(), block.col.size()});
  return absl::OkStatus();
}

absl::Status FileBlockSpill::Read(size_t index, RowBlock& out) const {
  if (index >= extents_.size()) {
    return absl::OutOfRangeError(
        absl::StrCat("spill file '", file_.path(), "' has no block ", index));
  }
  const Extent& e = extents_[index];
  uint64_t offset = e.offset;
  out.first_row = e.first_row;
  absl::Status s = ReadArray(file_, out.row_begin, e.rows + size_t{1}, offset);
  if (s.ok()) s = ReadArray(file_, out.col, e.nnz, offset);
  if (s.ok()) s = ReadArray(file_, out.value, e.nnz, offset);
  return s;
}

}  // namespace radflux
