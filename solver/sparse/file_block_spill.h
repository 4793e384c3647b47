// FileBlockSpill: a BlockSpill in one raw binary file (row offsets, columns, values per
// block, back to back) inside a directory. The file is unlinked as soon as it is created,
// so it disappears when the spill is destroyed or the process dies; a directory the spill
// created itself (no directory given) is removed by the destructor.
#pragma once

#include <string>
#include <vector>

#include "solver/sparse/block_spill.h"

namespace radflux {

class FileBlockSpill : public BlockSpill {
 public:
  // `directory`: where the file goes; "" = a fresh radflux-spill-XXXXXX under $TMPDIR or
  // /tmp. Nothing is created before the first Write.
  explicit FileBlockSpill(std::string directory);
  ~FileBlockSpill() override;
  FileBlockSpill(const FileBlockSpill&) = delete;
  FileBlockSpill& operator=(const FileBlockSpill&) = delete;

  absl::Status Write(const RowBlock& block) override;
  absl::Status Read(size_t index, RowBlock& out) const override;
  uint64_t BytesWritten() const override { return end_; }
  // The file's path while open ("" before the first Write); it is already unlinked.
  const std::string& path() const { return path_; }

 private:
  struct Extent {
    uint64_t offset = 0;
    uint32_t first_row = 0, rows = 0;
    uint64_t nnz = 0;
  };
  absl::Status Open();

  std::string directory_;
  std::string owned_directory_;  // created by us, removed by the destructor
  std::string path_;
  int fd_ = -1;
  uint64_t end_ = 0;
  std::vector<Extent> extents_;
};

}  // namespace radflux
