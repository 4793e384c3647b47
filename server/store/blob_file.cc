#include "server/store/blob_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zstd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "absl/strings/str_cat.h"
#include "server/store/disk_space.h"
#include "wire/scene_hash.h"

namespace radflux {
namespace {

constexpr std::string_view kMagic = "RFBLOB1\n";
constexpr size_t kHashHexSize = 64;
constexpr int kZstdLevel = 1;  // fastest: row blocks are written while rows are built

// Writes all of `data` to fd and, with `sync`, fsyncs it: 0, or the errno of the failure
// (ENOSPC for a write that stopped short, as a full disk does).
int WriteAll(int fd, std::string_view data, bool sync) {
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno;
    if (n == 0) return ENOSPC;
    data.remove_prefix(static_cast<size_t>(n));
  }
  return sync && ::fsync(fd) != 0 ? errno : 0;
}

std::string ParentDir(const std::string& path) {
  return std::filesystem::path(path).parent_path().string();
}

// The header of a blob of `raw_size` bytes with hex SHA-256 `hash`: the bytes before its frames.
std::string BlobHeader(uint64_t raw_size, std::string_view hash) {
  return absl::StrCat(std::string(kMagic), raw_size, "\n", std::string(hash), "\n");
}

// Appends `data` compressed as one zstd frame to `frames`.
absl::Status AppendFrame(std::string& frames, std::string_view data) {
  const size_t at = frames.size();
  frames.resize(at + ZSTD_compressBound(data.size()));
  const size_t size =
      ZSTD_compress(frames.data() + at, frames.size() - at, data.data(), data.size(), kZstdLevel);
  if (ZSTD_isError(size)) {
    frames.resize(at);
    return absl::InternalError(ZSTD_getErrorName(size));
  }
  frames.resize(at + size);
  return absl::OkStatus();
}

}  // namespace

bool SyncPath(const std::string& path) {
  const int fd = ::open(path.empty() ? "." : path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

BlobBuilder::BlobBuilder() : hash_(std::make_unique<Sha256Stream>()) {}
BlobBuilder::~BlobBuilder() = default;
BlobBuilder::BlobBuilder(BlobBuilder&&) noexcept = default;
BlobBuilder& BlobBuilder::operator=(BlobBuilder&&) noexcept = default;

absl::Status BlobBuilder::Append(std::string_view data) {
  if (absl::Status s = AppendFrame(frames_, data); !s.ok()) return s;
  hash_->Update(data);
  raw_size_ += data.size();
  return absl::OkStatus();
}

std::string BlobBuilder::File() const {
  return absl::StrCat(BlobHeader(raw_size_, hash_->Hex()), frames_);
}

namespace {

absl::StatusOr<std::string> EncodeBlob(std::string_view data) {
  BlobBuilder blob;
  if (absl::Status s = blob.Append(data); !s.ok()) return s;
  return blob.File();
}

}  // namespace

absl::Status WriteBlobFile(const std::string& path, std::string_view data, std::string_view what) {
  absl::StatusOr<std::string> blob = EncodeBlob(data);
  if (!blob.ok()) return blob.status();
  return WriteBuiltBlobFile(path, *blob, what);
}

absl::Status WriteBuiltBlobFile(const std::string& path, std::string_view file,
                                std::string_view what) {
  // A temp name of this writer's own: writers of the same blob (one scene uploaded by many
  // at once) each rename a whole file of the same bytes into place.
  std::string temp = path + ".tmp.XXXXXX";
  const int fd = ::mkostemp(temp.data(), O_CLOEXEC);
  if (fd < 0) return DiskWriteError(what, path, errno);
  int error = ::fchmod(fd, 0644) != 0 ? errno : WriteAll(fd, file, /*sync=*/true);
  ::close(fd);
  if (error == 0 && ::rename(temp.c_str(), path.c_str()) != 0) error = errno;
  if (error != 0) {
    ::unlink(temp.c_str());  // no partial file stays behind
    return DiskWriteError(what, path, error);
  }
  SyncPath(ParentDir(path));  // the rename itself
  return absl::OkStatus();
}

absl::StatusOr<std::unique_ptr<StreamedBlobFile>> StreamedBlobFile::Create(
    const std::string& dir, uint64_t raw_size, std::string what) {
  std::string temp = dir + "/upload.XXXXXX";
  const int fd = ::mkostemp(temp.data(), O_CLOEXEC);
  if (fd < 0) return DiskWriteError(what, temp, errno);
  std::unique_ptr<StreamedBlobFile> file(new StreamedBlobFile(temp, fd, raw_size, what));
  // The hash is not known yet: zeros of its length now, the digest at Finish.
  const std::string header = BlobHeader(raw_size, std::string(kHashHexSize, '0'));
  const int error = ::fchmod(fd, 0644) != 0 ? errno : WriteAll(fd, header, /*sync=*/false);
  if (error != 0) return DiskWriteError(what, temp, error);
  return file;
}

StreamedBlobFile::StreamedBlobFile(std::string temp, int fd, uint64_t raw_size, std::string what)
    : temp_(std::move(temp)), fd_(fd), raw_size_(raw_size), what_(std::move(what)) {}

StreamedBlobFile::~StreamedBlobFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(temp_.c_str());
}

absl::Status StreamedBlobFile::Append(std::string_view data) {
  if (data.empty()) return absl::OkStatus();
  frame_.clear();
  if (absl::Status s = AppendFrame(frame_, data); !s.ok()) return s;
  if (const int error = WriteAll(fd_, frame_, /*sync=*/false); error != 0) {
    return DiskWriteError(what_, temp_, error);
  }
  hash_.Update(data);
  got_ += data.size();
  framed_ = true;
  return absl::OkStatus();
}

absl::Status StreamedBlobFile::Finish() {
  if (got_ != raw_size_) {
    return absl::DataLossError(absl::StrCat(what_, ": got ", got_, " of ", raw_size_, " bytes"));
  }
  if (!framed_) {  // a blob has at least one frame (ReadBlobFile decompresses one)
    frame_.clear();
    if (absl::Status s = AppendFrame(frame_, {}); !s.ok()) return s;
    if (const int error = WriteAll(fd_, frame_, false); error != 0) {
      return DiskWriteError(what_, temp_, error);
    }
  }
  const std::string hash = hash_.Hex();
  const off_t at = static_cast<off_t>(BlobHeader(raw_size_, hash).size() - kHashHexSize - 1);
  if (::pwrite(fd_, hash.data(), hash.size(), at) != static_cast<ssize_t>(hash.size()) ||
      ::fsync(fd_) != 0) {
    return DiskWriteError(what_, temp_, errno);
  }
  return absl::OkStatus();
}

absl::Status StreamedBlobFile::Commit(const std::string& path) {
  if (::rename(temp_.c_str(), path.c_str()) != 0) return DiskWriteError(what_, path, errno);
  committed_ = true;
  SyncPath(ParentDir(path));
  return absl::OkStatus();
}

absl::Status CreateDurableFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return DiskWriteError("an empty file", path, errno);
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  const std::string dir = ParentDir(path);
  if (!ok || !SyncPath(dir) || !SyncPath(ParentDir(dir))) {
    return DiskWriteError("an empty file", path, errno);
  }
  return absl::OkStatus();
}

absl::Status WriteBuiltBlobFileInPlace(const std::string& path, std::string_view file,
                                       std::string_view what) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return DiskWriteError(what, path, errno);
  int error = WriteAll(fd, file, /*sync=*/false);
  if (error == 0 && ::ftruncate(fd, static_cast<off_t>(file.size())) != 0) error = errno;
  ::close(fd);
  if (error != 0) return DiskWriteError(what, path, error);
  return absl::OkStatus();
}

namespace {

// Decompresses the frames in `in` into `parts`, in order, filling each exactly; false when
// the frames hold fewer or more bytes than the parts, or are not valid zstd.
bool DecompressInto(ZSTD_inBuffer in, std::vector<std::string>& parts) {
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(), ZSTD_freeDCtx);
  char spare = 0;  // after the parts: any byte more is too many
  size_t left = 1;
  for (size_t k = 0; k <= parts.size(); ++k) {
    const bool last = k == parts.size();
    ZSTD_outBuffer out{last ? &spare : parts[k].data(), last ? 1 : parts[k].size(), 0};
    while (last ? in.pos < in.size : out.pos < out.size) {
      const size_t in_before = in.pos;
      const size_t out_before = out.pos;
      left = ZSTD_decompressStream(context.get(), &out, &in);
      if (ZSTD_isError(left) || (last && out.pos > 0)) return false;
      if (in.pos == in_before && out.pos == out_before) return false;  // truncated
    }
  }
  return left == 0;  // the last frame is whole
}

}  // namespace

absl::StatusOr<std::string> ReadBlobFile(const std::string& path) {
  absl::StatusOr<std::vector<std::string>> parts = ReadBlobFileParts(path, {});
  if (!parts.ok()) return parts.status();
  return std::move(parts->front());
}

absl::StatusOr<std::vector<std::string>> ReadBlobFileParts(const std::string& path,
                                                           std::vector<uint64_t> sizes) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return absl::NotFoundError(absl::StrCat("no such blob: ", path));
  std::string file(static_cast<size_t>(in.tellg()), '\0');  // read once, not copied
  in.seekg(0);
  if (!in.read(file.data(), static_cast<std::streamsize>(file.size()))) {
    return absl::DataLossError(absl::StrCat("cannot read blob ", path));
  }
  const auto corrupt = [&](std::string_view why) {
    return absl::DataLossError(absl::StrCat("corrupt blob ", path, ": ", std::string(why)));
  };
  if (file.compare(0, kMagic.size(), kMagic) != 0) return corrupt("bad magic");
  const size_t size_end = file.find('\n', kMagic.size());
  if (size_end == std::string::npos) return corrupt("truncated header");
  const std::string size_text = file.substr(kMagic.size(), size_end - kMagic.size());
  const size_t hash_begin = size_end + 1;
  if (file.size() < hash_begin + kHashHexSize + 1) return corrupt("truncated header");
  const std::string hash = file.substr(hash_begin, kHashHexSize);
  const size_t body = hash_begin + kHashHexSize + 1;
  char* end = nullptr;
  const unsigned long long raw_size = std::strtoull(size_text.c_str(), &end, 10);
  if (end == size_text.c_str() || *end != '\0') return corrupt("bad size");
  if (sizes.empty()) sizes.push_back(raw_size);
  uint64_t total = 0;
  for (uint64_t size : sizes) {
    if (__builtin_add_overflow(total, size, &total)) return corrupt("parts overflow");
  }
  if (total != raw_size) {
    return corrupt(absl::StrCat(raw_size, " bytes, not the ", total, " of its parts"));
  }
  std::vector<std::string> parts;
  for (uint64_t size : sizes) parts.emplace_back(size, '\0');
  if (!DecompressInto({file.data() + body, file.size() - body, 0}, parts)) {
    return corrupt("bad compressed data");
  }
  Sha256Stream digest;
  for (const std::string& part : parts) digest.Update(part);
  if (digest.Hex() != hash) return corrupt("checksum mismatch");
  return parts;
}

}  // namespace radflux
