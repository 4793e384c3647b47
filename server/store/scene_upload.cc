#include "server/store/scene_upload.h"

#include <algorithm>
#include <filesystem>

#include "absl/strings/str_cat.h"

namespace radflux {

absl::StatusOr<std::vector<BundleFile>> ReadBundleBlob(const std::string& path,
                                                       const v1::SceneHeader& index) {
  std::vector<uint64_t> sizes;
  for (const v1::BundleFile& file : index.files()) sizes.push_back(file.size());
  absl::StatusOr<std::vector<std::string>> parts = ReadBlobFileParts(path, sizes);
  if (!parts.ok()) return parts.status();
  std::vector<BundleFile> files;
  for (int i = 0; i < index.files_size(); ++i) {
    files.push_back({index.files(i).path(), std::move((*parts)[i])});
  }
  return files;
}

absl::StatusOr<std::unique_ptr<SceneUpload>> SceneUpload::Start(const std::string& scenes_dir,
                                                                 const v1::SceneHeader& header) {
  const absl::StatusOr<uint64_t> size = ScenePayloadSize(header);
  if (!size.ok()) return size.status();
  std::unique_ptr<SceneUpload> upload(new SceneUpload(header));
  upload->expected_ = *size;
  std::vector<std::pair<std::string, uint64_t>> parts;  // suffix, size
  if (header.files_size() > 0) {
    parts = {{".bundle.rfb", *size}};  // hashed when read back: its order is not the stream's
  } else if (header.mesh_size() > 0) {
    parts = {{".mesh.rfb", *size}};
    upload->hash_.emplace().Update(kMeshHashPrefix);
  } else {
    parts = {{".obj.rfb", header.obj_size()}, {".mtl.rfb", header.mtl_size()}};
    upload->hash_.emplace().Update(SceneHashPrefix(header.obj_size()));
  }
  for (const auto& [suffix, bytes] : parts) {
    absl::StatusOr<std::unique_ptr<StreamedBlobFile>> file =
        StreamedBlobFile::Create(scenes_dir, bytes, "an uploaded scene");
    if (!file.ok()) return file.status();
    upload->parts_.push_back({suffix, bytes, *std::move(file)});
  }
  upload->part_end_ = upload->parts_[0].size;
  return upload;
}

absl::Status SceneUpload::Append(std::string_view data) {
  if (data.size() > expected_ - received_) {
    return absl::DataLossError(
        absl::StrCat("upload is longer than the ", expected_, " bytes its header declares"));
  }
  if (hash_) hash_->Update(data);
  while (!data.empty()) {
    while (received_ == part_end_) part_end_ += parts_[++part_].size;
    const size_t n = static_cast<size_t>(std::min<uint64_t>(part_end_ - received_, data.size()));
    if (absl::Status s = parts_[part_].file->Append(data.substr(0, n)); !s.ok()) return s;
    received_ += n;
    data.remove_prefix(n);
  }
  return absl::OkStatus();
}

absl::StatusOr<StoredScene> SceneUpload::Finish(std::string* sha256) {
  if (received_ != expected_) {
    return absl::DataLossError(
        absl::StrCat("upload truncated: got ", received_, " of ", expected_, " bytes"));
  }
  for (Part& part : parts_) {
    if (absl::Status s = part.file->Finish(); !s.ok()) return s;
  }
  StoredScene scene;
  if (header_.files_size() > 0) {
    absl::StatusOr<std::vector<BundleFile>> files =
        ReadBundleBlob(parts_[0].file->temp_path(), header_);
    if (!files.ok()) return files.status();
    scene.files = *std::move(files);
  } else {
    std::vector<std::string*> texts = {&scene.mesh};
    if (header_.mesh_size() == 0) texts = {&scene.obj, &scene.mtl};
    for (size_t k = 0; k < parts_.size(); ++k) {
      absl::StatusOr<std::string> text = ReadBlobFile(parts_[k].file->temp_path());
      if (!text.ok()) return text.status();
      *texts[k] = *std::move(text);
    }
  }
  scene.name = header_.name();
  *sha256 = hash_ ? hash_->Hex() : StoredSceneHash(scene);
  return scene;
}

absl::Status SceneUpload::Commit(const std::string& base) {
  absl::Status status;
  for (Part& part : parts_) {
    status = part.file->Commit(base + part.suffix);
    if (!status.ok()) break;
  }
  if (status.ok() && header_.files_size() > 0) {
    v1::SceneHeader index;  // the files' paths and sizes; their bytes are in .bundle.rfb
    for (const v1::BundleFile& file : header_.files()) {
      v1::BundleFile* entry = index.add_files();
      entry->set_path(file.path());
      entry->set_size(file.size());
    }
    status = WriteBlobFile(base + ".files.rfb", index.SerializeAsString(), "a scene");
  }
  if (!status.ok()) {  // no part of the scene stays behind
    std::error_code ec;
    for (const Part& part : parts_) std::filesystem::remove(base + part.suffix, ec);
  }
  return status;
}

}  // namespace radflux
