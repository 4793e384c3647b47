#include "server/store/disk_space.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"

namespace radflux {

absl::Status DiskWriteError(std::string_view what, const std::string& path, int error_number) {
  const std::string why =
      error_number == 0 ? "short write" : std::string(std::strerror(error_number));
  if (error_number == ENOSPC || error_number == EDQUOT) {
    return absl::ResourceExhaustedError(
        absl::StrCat("disk full writing ", std::string(what), " at ", path, ": ", why));
  }
  return absl::InternalError(absl::StrCat("cannot write ", std::string(what), " at ", path, ": ", why));
}

absl::StatusOr<uint64_t> FreeDiskBytes(const std::string& dir) {
  struct statvfs fs {};
  if (::statvfs(dir.c_str(), &fs) != 0) {
    return absl::InternalError(absl::StrCat("cannot statvfs ", dir, ": ", std::strerror(errno)));
  }
  return static_cast<uint64_t>(fs.f_bavail) * fs.f_frsize;
}

uint64_t DirectoryBytes(const std::string& dir) {
  uint64_t bytes = 0;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    std::error_code size_error;
    if (it->is_regular_file(size_error)) {
      const uintmax_t size = it->file_size(size_error);
      if (!size_error) bytes += size;
    }
  }
  return bytes;
}

bool IsDiskFull(const absl::Status& status) {
  return status.code() == absl::StatusCode::kResourceExhausted &&
         absl::StrContains(status.message(), "disk full");
}

absl::Status SpaceReserve::Ensure() {
  if (held_) return absl::OkStatus();
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) return DiskWriteError("the space reserve", path_, errno);
  const int error = ::posix_fallocate(fd, 0, static_cast<off_t>(kReserveBytes));
  ::close(fd);
  if (error != 0) {
    ::unlink(path_.c_str());  // a part of a reserve would only hold space back
    return DiskWriteError("the space reserve", path_, error);
  }
  held_ = true;
  return absl::OkStatus();
}

bool SpaceReserve::Release() {
  const bool had = ::unlink(path_.c_str()) == 0;
  held_ = false;
  return had;
}

}  // namespace radflux
