#include "server/store/blob_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <openssl/evp.h>
#include <unistd.h>
#include <zstd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

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

}  // namespace

bool SyncPath(const std::string& path) {
  const int fd = ::open(path.empty() ? "." : path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

struct BlobBuilder::Hash {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx{EVP_MD_CTX_new(), EVP_MD_CTX_free};
};

BlobBuilder::BlobBuilder() : hash_(std::make_unique<Hash>()) {
  EVP_DigestInit_ex(hash_->ctx.get(), EVP_sha256(), nullptr);
}
BlobBuilder::~BlobBuilder() = default;
BlobBuilder::BlobBuilder(BlobBuilder&&) noexcept = default;
BlobBuilder& BlobBuilder::operator=(BlobBuilder&&) noexcept = default;

absl::Status BlobBuilder::Append(std::string_view data) {
  const size_t at = frames_.size();
  frames_.resize(at + ZSTD_compressBound(data.size()));
  const size_t size =
      ZSTD_compress(frames_.data() + at, frames_.size() - at, data.data(), data.size(), kZstdLevel);
  if (ZSTD_isError(size)) {
    frames_.resize(at);
    return absl::InternalError(ZSTD_getErrorName(size));
  }
  frames_.resize(at + size);
  EVP_DigestUpdate(hash_->ctx.get(), data.data(), data.size());
  raw_size_ += data.size();
  return absl::OkStatus();
}

std::string BlobBuilder::File() const {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_MD_CTX_copy_ex(ctx.get(), hash_->ctx.get());
  return absl::StrCat(std::string(kMagic), raw_size_, "\n", DigestHex(ctx.get()), "\n", frames_);
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

absl::StatusOr<std::string> ReadBlobFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat("no such blob: ", path));
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string file = buffer.str();
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
  std::string raw(raw_size, '\0');
  const size_t got =
      ZSTD_decompress(raw.data(), raw.size(), file.data() + body, file.size() - body);
  if (ZSTD_isError(got) || got != raw_size) return corrupt("bad compressed data");
  if (Sha256Hex(raw) != hash) return corrupt("checksum mismatch");
  return raw;
}

}  // namespace radflux
