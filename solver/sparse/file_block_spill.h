// FileBlockSpill: a BlockSpill in one raw binary file (row offsets, columns, values per
// block, back to back) inside a directory: a SpillFile (spill_file.h), unlinked as soon as it
// is created, so it disappears when the spill is destroyed or the process dies; a directory
// the spill created itself (no directory given) is removed by the destructor.
#pragma once

#include <string>
#include <vector>

#include "solver/sparse/block_spill.h"
#include "solver/sparse/spill_file.h"

namespace radflux {

class FileBlockSpill : public BlockSpill {
 public:
  // `directory`: where the file goes; "" = a fresh radflux-spill-XXXXXX under $TMPDIR or
  // /tmp. Nothing is created before the first Write.
  explicit FileBlockSpill(std::string directory);

  absl::Status Write(const RowBlock& block) override;
  absl::Status Read(size_t index, RowBlock& out) const override;
  uint64_t BytesWritten() const override { return file_.size(); }
  // The file's path while open ("" before the first Write); it is already unlinked.
  const std::string& path() const { return file_.path(); }

 private:
  struct Extent {
    uint64_t offset = 0;
    uint32_t first_row = 0, rows = 0;
    uint64_t nnz = 0;
  };

  SpillFile file_;
  std::vector<Extent> extents_;
};

}  // namespace radflux
