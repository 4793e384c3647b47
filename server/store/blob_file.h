// Blob files: the job store's on-disk format for row blocks, checkpoints, scenes and
// results. A blob is zstd-compressed with a header carrying the raw size and the SHA-256
// of the raw bytes; it is written atomically (temp file, fsync, rename, fsync of the dir),
// so a reader sees either the whole previous file, the whole new one, or none; or, for a
// file no one reads before a later commit, in place without an fsync of its own
// (WriteBuiltBlobFileInPlace, then SyncPath).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "wire/scene_hash.h"

namespace radflux {

// A blob built from pieces as they become known: each Append compresses its piece as one
// zstd frame and adds it to the SHA-256 of the raw bytes, so that what is known early (a
// result's mesh) is compressed and hashed before the rest exists. File() is what
// WriteBlobFile would write for the concatenation of the pieces, except that the
// compressed data is one frame per piece (ReadBlobFile reads both alike: zstd decompresses
// concatenated frames as one).
class BlobBuilder {
 public:
  BlobBuilder();
  ~BlobBuilder();
  BlobBuilder(BlobBuilder&&) noexcept;
  BlobBuilder& operator=(BlobBuilder&&) noexcept;

  absl::Status Append(std::string_view data);
  // The blob file's bytes: header (magic, raw size, SHA-256), then the frames.
  std::string File() const;

 private:
  std::unique_ptr<Sha256Stream> hash_;  // of the raw bytes; null after a move
  uint64_t raw_size_ = 0;
  std::string frames_;
};

// A blob file written as its bytes arrive (an upload): under a unique temp name in a
// directory (mkostemp, "upload.XXXXXX"), each Append compressed as one zstd frame and
// hashed, its raw size declared up front; Finish writes the SHA-256 into the header and
// fsyncs; Commit renames it into place. The temp file is removed by the destructor unless
// committed (a failed or cancelled upload leaves nothing behind).
class StreamedBlobFile {
 public:
  // The temp file in `dir` for `raw_size` bytes of `what` (named in errors).
  static absl::StatusOr<std::unique_ptr<StreamedBlobFile>> Create(const std::string& dir,
                                                                  uint64_t raw_size,
                                                                  std::string what);
  ~StreamedBlobFile();
  StreamedBlobFile(const StreamedBlobFile&) = delete;
  StreamedBlobFile& operator=(const StreamedBlobFile&) = delete;

  // Adds raw bytes (the caller keeps their sum within raw_size).
  absl::Status Append(std::string_view data);
  // DATA_LOSS unless raw_size bytes came; else completes the header and fsyncs: the temp
  // file is then a whole blob that ReadBlobFile(temp_path()) verifies.
  absl::Status Finish();
  // Atomically replaces `path` with the finished file (rename; fsync of the directory).
  absl::Status Commit(const std::string& path);
  const std::string& temp_path() const { return temp_; }

 private:
  StreamedBlobFile(std::string temp, int fd, uint64_t raw_size, std::string what);

  std::string temp_;
  int fd_;
  uint64_t raw_size_;
  std::string what_;
  uint64_t got_ = 0;            // raw bytes appended
  bool framed_ = false;         // a frame was written (an empty blob gets one at Finish)
  bool committed_ = false;
  std::string frame_;           // compression buffer, reused
  Sha256Stream hash_;           // of the raw bytes
};

// fsyncs `path` (a file or a directory); false when it cannot be opened or synced.
bool SyncPath(const std::string& path);

// Compresses `data` and atomically replaces `path` with it. A failed write leaves no temp
// file behind and says what failed (DiskWriteError: `what` names the data, e.g. "row blocks";
// RESOURCE_EXHAUSTED "disk full writing ..." when the disk is full).
absl::Status WriteBlobFile(const std::string& path, std::string_view data,
                           std::string_view what = "a blob");

// Creates `path` if absent (empty; an existing file is left as it is) and makes it and its
// name durable: fsync of the file, of its directory and of that directory's parent, so a
// file in a directory created just before survives an OS crash too.
absl::Status CreateDurableFile(const std::string& path);

// WriteBlobFile of a blob built already (`file`: BlobBuilder::File()).
absl::Status WriteBuiltBlobFile(const std::string& path, std::string_view file,
                                std::string_view what = "a blob");
// Writes a built blob into the existing file `path` (see CreateDurableFile) without an
// fsync: it survives kill -9, and SyncPath(path) makes it durable. Not atomic: until it
// returns, and after a crash while it runs, the file may hold a partial blob (which
// ReadBlobFile reports as DATA_LOSS), so it is for files that no one reads before a later
// commit says they are complete (and a caller removes after a failed write).
absl::Status WriteBuiltBlobFileInPlace(const std::string& path, std::string_view file,
                                       std::string_view what = "a blob");

// Reads and verifies a blob: NOT_FOUND when absent, DATA_LOSS when truncated or corrupt.
absl::StatusOr<std::string> ReadBlobFile(const std::string& path);

// ReadBlobFile of a blob whose bytes are parts of `sizes` one after another, each
// decompressed straight into its own string (no copy of the whole); DATA_LOSS also when
// the sizes do not add up to the blob's. Empty `sizes`: one part, the whole blob.
absl::StatusOr<std::vector<std::string>> ReadBlobFileParts(const std::string& path,
                                                           std::vector<uint64_t> sizes);

}  // namespace radflux
