// JobStore's files of one job under jobs/<id>/: row blocks, the solver checkpoint and the
// result (see job_store.h).
#include <spdlog/spdlog.h>

#include <filesystem>
#include <map>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "server/store/blob_file.h"
#include "server/store/job_store.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

std::string RowBlockName(uint32_t index) { return absl::StrCat("rows_", index, ".rfb"); }

}  // namespace

std::string JobStore::ResultPath(const std::string& job_id) const {
  return (fs::path(JobDir(job_id)) / "result.rfb").string();
}

absl::Status JobStore::PutRowBlocks(const std::string& job_id, uint32_t name_index,
                                    const std::vector<const StoredRowBlock*>& blocks) {
  return WriteBlobFile((fs::path(JobDir(job_id)) / RowBlockName(name_index)).string(),
                       EncodeRowBlockGroup(blocks), "row blocks");
}

void JobStore::ForEachRowBlock(const std::string& job_id,
                               const std::function<void(StoredRowBlock)>& fn,
                               std::vector<absl::Status>* unreadable) {
  std::map<uint32_t, fs::path> files;  // by the index in their name
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(JobDir(job_id), ec)) {
    const std::string name = entry.path().stem().string();
    uint32_t index = 0;
    if (name.rfind("rows_", 0) != 0 || entry.path().extension() != ".rfb" ||
        !absl::SimpleAtoi(name.substr(5), &index)) {
      continue;
    }
    files.emplace(index, entry.path());
  }
  for (const auto& [index, path] : files) {
    absl::StatusOr<std::string> bytes = ReadBlobFile(path.string());
    absl::StatusOr<std::vector<StoredRowBlock>> group =
        bytes.ok() ? DecodeRowBlockGroup(*bytes) : bytes.status();
    if (!group.ok()) {
      unreadable->push_back(
          absl::DataLossError(absl::StrCat(path.string(), ": ", group.status().message())));
      continue;
    }
    for (StoredRowBlock& block : *group) fn(std::move(block));
  }
}

absl::Status JobStore::PutCheckpoint(const std::string& job_id, const SolverCheckpoint& c) {
  return WriteBlobFile((fs::path(JobDir(job_id)) / "checkpoint.rfb").string(), EncodeCheckpoint(c),
                       "a solver checkpoint");
}

absl::StatusOr<SolverCheckpoint> JobStore::GetCheckpoint(const std::string& job_id) {
  absl::StatusOr<std::string> bytes =
      ReadBlobFile((fs::path(JobDir(job_id)) / "checkpoint.rfb").string());
  if (!bytes.ok()) return bytes.status();
  return DecodeCheckpoint(*bytes);
}

absl::Status JobStore::PrepareResult(const std::string& job_id) {
  std::error_code ec;
  fs::create_directories(JobDir(job_id), ec);
  if (ec) return absl::InternalError(absl::StrCat("cannot create ", JobDir(job_id)));
  return CreateDurableFile(ResultPath(job_id));
}

absl::Status JobStore::PutResult(const std::string& job_id, std::string_view file, bool prepared) {
  const std::string path = ResultPath(job_id);
  absl::Status s = prepared ? WriteBuiltBlobFileInPlace(path, file, "the result")
                            : WriteBuiltBlobFile(path, file, "the result");
  std::error_code ec;
  if (!s.ok()) fs::remove(path, ec);  // a part of a result is no result
  return s;
}

absl::Status JobStore::SyncResult(const std::string& job_id) {
  const std::string path = ResultPath(job_id);
  if (!SyncPath(path)) return absl::InternalError(absl::StrCat("cannot fsync ", path));
  return absl::OkStatus();
}

absl::StatusOr<std::string> JobStore::GetResult(const std::string& job_id) {
  absl::StatusOr<std::string> read = ReadBlobFile(ResultPath(job_id));
  if (read.ok()) return read;
  spdlog::error("job {}: {}", job_id, std::string(read.status().message()));  // with its path
  return absl::Status(read.status().code(),
                      absl::StrCat("job ", job_id, ": its stored result is ",
                                   absl::IsNotFound(read.status()) ? "lost" : "corrupt",
                                   " on the server"));
}

void JobStore::DiscardResult(const std::string& job_id) {
  std::error_code ec;
  fs::remove(ResultPath(job_id), ec);
  fs::remove(fs::path(JobDir(job_id)) / "checkpoint.rfb", ec);
}

void JobStore::RemoveWorkFiles(const std::string& job_id) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(JobDir(job_id), ec)) {
    const bool result = entry.path().filename() == "result.rfb" && entry.file_size(ec) > 0;
    if (!result) fs::remove(entry.path(), ec);
  }
}

}  // namespace radflux
