#include "solver/output/output_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

absl::Status WriteError(absl::string_view kind, const std::string& path, int error) {
  return absl::Status(
      absl::ErrnoToStatusCode(error),
      absl::StrCat("cannot write ", kind, " file '", path, "': ", std::strerror(error)));
}

}  // namespace

absl::Status WriteOutputFile(const std::string& path, absl::string_view bytes,
                             absl::string_view kind) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) return WriteError(kind, path, errno);
  const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), file);
  const int write_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (written != bytes.size()) return WriteError(kind, path, write_errno);
  if (!closed) return WriteError(kind, path, errno);
  return absl::OkStatus();
}

}  // namespace radflux
