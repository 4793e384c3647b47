#include "solver/sparse/spill_file.h"

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

}  // namespace

SpillFile::SpillFile(std::string directory, std::string name)
    : directory_(std::move(directory)), name_(std::move(name)) {}

SpillFile::~SpillFile() {
  if (fd_ >= 0) close(fd_);
  if (!owned_directory_.empty()) rmdir(owned_directory_.c_str());
}

absl::Status SpillFile::Open() {
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
  std::string pattern = absl::StrCat(directory, "/", name_, "-XXXXXX.spill");
  fd_ = mkstemps(pattern.data(), 6);
  if (fd_ < 0) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot create a spill file in '", directory, "': ", ErrnoText(errno)));
  }
  path_ = pattern;
  unlink(path_.c_str());  // the open descriptor keeps the data; nothing is left behind
  return absl::OkStatus();
}

absl::StatusOr<uint64_t> SpillFile::Append(const void* data, size_t bytes) {
  if (fd_ < 0) {
    if (absl::Status s = Open(); !s.ok()) return s;
  }
  const uint64_t offset = end_;
  if (absl::Status s = TransferAll(pwrite, fd_, static_cast<const char*>(data), bytes, offset,
                                   "spill file '" + path_ + "': writing");
      !s.ok()) {
    return s;
  }
  end_ += bytes;
  return offset;
}

absl::Status SpillFile::Read(uint64_t offset, void* data, size_t bytes) const {
  return TransferAll(pread, fd_, static_cast<char*>(data), bytes, offset,
                     "spill file '" + path_ + "': reading");
}

}  // namespace radflux
