#include "solver/sparse/file_block_spill.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

std::string ErrnoText(int error) { return std::strerror(error); }

// Writes or reads all `size` bytes at `offset`, retrying short transfers and EINTR.
template <typename Transfer, typename Byte>
absl::Status TransferAll(Transfer transfer, int fd, Byte* data, size_t size, uint64_t offset,
                         const std::string& what) {
  while (size > 0) {
    const ssize_t done = transfer(fd, data, size, static_cast<off_t>(offset));
    if (done < 0 && errno == EINTR) continue;
    if (done <= 0) {
      const int error = done == 0 ? 0 : errno;
      const std::string message =
          absl::StrCat(what, " ", size, " bytes at offset ", offset,
                       " failed: ", error == 0 ? "unexpected end of file" : ErrnoText(error));
      if (error == ENOSPC || error == EDQUOT) {
        return absl::ResourceExhaustedError(absl::StrCat(message, " (disk full)"));
      }
      return absl::DataLossError(message);
    }
    data += done;
    size -= static_cast<size_t>(done);
    offset += static_cast<uint64_t>(done);
  }
  return absl::OkStatus();
}

template <typename T>
absl::Status WriteArray(int fd, const std::vector<T>& v, uint64_t& offset,
                        const std::string& path) {
  const size_t bytes = v.size() * sizeof(T);
  absl::Status s = TransferAll(pwrite, fd, reinterpret_cast<const char*>(v.data()), bytes, offset,
                               "spill file '" + path + "': writing");
  offset += bytes;
  return s;
}

template <typename T>
absl::Status ReadArray(int fd, std::vector<T>& v, size_t count, uint64_t& offset,
                       const std::string& path) {
  v.resize(count);
  const size_t bytes = count * sizeof(T);
  absl::Status s = TransferAll(pread, fd, reinterpret_cast<char*>(v.data()), bytes, offset,
                               "spill file '" + path + "': reading");
  offset += bytes;
  return s;
}

}  // namespace

FileBlockSpill::FileBlockSpill(std::string directory) : directory_(std::move(directory)) {}

FileBlockSpill::~FileBlockSpill() {
  if (fd_ >= 0) close(fd_);
  if (!owned_directory_.empty()) rmdir(owned_directory_.c_str());
}

absl::Status FileBlockSpill::Open() {
  std::string directory = directory_;
  if (directory.empty()) {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern =
        absl::StrCat(tmp != nullptr && *tmp ? tmp : "/tmp", "/radflux-spill-XXXXXX");
    if (mkdtemp(pattern.data()) == nullptr) {
      return absl::FailedPreconditionError(
          absl::StrCat("cannot create a spill directory '", pattern, "': ", ErrnoText(errno)));
    }
    owned_directory_ = directory = pattern;
  }
  std::string pattern = directory + "/rows-XXXXXX.spill";
  fd_ = mkstemps(pattern.data(), 6);
  if (fd_ < 0) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot create a spill file in '", directory, "': ", ErrnoText(errno)));
  }
  path_ = pattern;
  unlink(path_.c_str());  // the open descriptor keeps the data; nothing is left behind
  return absl::OkStatus();
}

absl::Status FileBlockSpill::Write(const RowBlock& block) {
  if (fd_ < 0) {
    if (absl::Status s = Open(); !s.ok()) return s;
  }
  Extent extent{end_, block.first_row, block.RowCount(), block.col.size()};
  uint64_t offset = end_;
  absl::Status s = WriteArray(fd_, block.row_begin, offset, path_);
  if (s.ok()) s = WriteArray(fd_, block.col, offset, path_);
  if (s.ok()) s = WriteArray(fd_, block.value, offset, path_);
  if (!s.ok()) return s;
  end_ = offset;
  extents_.push_back(extent);
  return absl::OkStatus();
}

absl::Status FileBlockSpill::Read(size_t index, RowBlock& out) const {
  if (index >= extents_.size()) {
    return absl::OutOfRangeError(absl::StrCat("spill file '", path_, "' has no block ", index));
  }
  const Extent& e = extents_[index];
  uint64_t offset = e.offset;
  out.first_row = e.first_row;
  absl::Status s = ReadArray(fd_, out.row_begin, e.rows + size_t{1}, offset, path_);
  if (s.ok()) s = ReadArray(fd_, out.col, e.nnz, offset, path_);
  if (s.ok()) s = ReadArray(fd_, out.value, e.nnz, offset, path_);
  return s;
}

}  // namespace radflux
