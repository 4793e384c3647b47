// TinyFilesystem: a tmpfs of a few MiB mounted on a directory in a mount namespace of the
// test process's own (unshare(CLONE_NEWNS), so no other process sees it and nothing is
// left mounted when the test process ends), for tests of a disk that fills for real:
// radfluxd children forked after it inherit the namespace and write into the small
// filesystem, and Fill() takes every free byte with a ballast file, Drain() gives them
// back. Needs root (CAP_SYS_ADMIN), as CI has; without it the constructor fails the test.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace radflux::testing {

class TinyFilesystem {
 public:
  // Mounts a tmpfs of `bytes` on the existing directory `dir`; ok() tells whether it did.
  TinyFilesystem(std::string dir, size_t bytes) : dir_(std::move(dir)) {
    if (::unshare(CLONE_NEWNS) != 0 ||
        ::mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
        ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, ("size=" + std::to_string(bytes)).c_str()) != 0) {
      ADD_FAILURE() << "cannot mount a " << bytes << "-byte tmpfs on " << dir_ << ": "
                    << std::strerror(errno) << " (the test needs root, as CI runs it)";
      return;
    }
    mounted_ = true;
  }
  ~TinyFilesystem() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  TinyFilesystem(const TinyFilesystem&) = delete;
  TinyFilesystem& operator=(const TinyFilesystem&) = delete;

  bool ok() const { return mounted_; }
  // Appends to the ballast file until the filesystem refuses a byte more (ENOSPC).
  void Fill() {
    const int fd = ::open(Ballast().c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    ASSERT_GE(fd, 0) << std::strerror(errno);
    const std::string chunk(64 << 10, 'x');
    for (size_t size = chunk.size(); size > 0; size /= 2) {  // the last pages too
      while (::write(fd, chunk.data(), size) == static_cast<ssize_t>(size)) {
      }
    }
    const int error = errno;
    ::close(fd);
    EXPECT_EQ(error, ENOSPC) << std::strerror(error);
  }
  // Deletes the ballast file: the space is back.
  void Drain() { ::unlink(Ballast().c_str()); }

 private:
  std::string Ballast() const { return dir_ + "/ballast"; }

  std::string dir_;
  bool mounted_ = false;
};

}  // namespace radflux::testing
