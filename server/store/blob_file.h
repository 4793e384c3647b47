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

#include "absl/status/statusor.h"

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
  struct Hash;                  // the running SHA-256 (OpenSSL)
  std::unique_ptr<Hash> hash_;  // null after a move
  uint64_t raw_size_ = 0;
  std::string frames_;
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

}  // namespace radflux
