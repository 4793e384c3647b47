// SceneUpload: an UploadScene in progress. Its payload goes to disk as it arrives, into the
// blob files the scene is stored as (OBJ and MTL texts, a serialized Mesh, or a bundle's
// bytes) under unique temp names in the store's scenes/ directory, so memory holds one chunk
// at a time whatever the upload's size; the content address of texts and meshes is hashed
// as the bytes come. Finish reads the files back for the scene's checks; Commit renames
// them into place. Destroyed uncommitted (a failed, refused or cancelled upload), it leaves
// no file behind.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "radflux/v1/scene.pb.h"
#include "server/store/blob_file.h"
#include "wire/scene_hash.h"
#include "wire/stored_scene.h"

namespace radflux {

// The files of a bundle stored as one blob at `path` (.bundle.rfb), laid out as `index`
// lists them (paths and sizes), each read straight into its own string; DATA_LOSS when the
// blob is corrupt or its size is not theirs.
absl::StatusOr<std::vector<BundleFile>> ReadBundleBlob(const std::string& path,
                                                       const v1::SceneHeader& index);

class SceneUpload {
 public:
  // Starts an upload of the payload `header` declares (INVALID_ARGUMENT as ScenePayloadSize
  // says) into temp files in `scenes_dir`.
  static absl::StatusOr<std::unique_ptr<SceneUpload>> Start(const std::string& scenes_dir,
                                                            const v1::SceneHeader& header);
  SceneUpload(const SceneUpload&) = delete;
  SceneUpload& operator=(const SceneUpload&) = delete;

  // Writes the payload's next bytes: DATA_LOSS (nothing written) past the declared size.
  absl::Status Append(std::string_view data);
  // The stream ended: DATA_LOSS when it was shorter than declared; else the files are
  // completed and fsynced and read back, verified, as the scene, and *sha256 is its content
  // address (StoredSceneHash of the same bytes). The scene is in memory from here on.
  absl::StatusOr<StoredScene> Finish(std::string* sha256);
  // After Finish: renames the files to `base` + their suffixes (.obj.rfb and .mtl.rfb,
  // .mesh.rfb, or .bundle.rfb and its index .files.rfb), as JobStore reads a stored scene;
  // on a failure no part of it stays.
  absl::Status Commit(const std::string& base);

 private:
  struct Part {
    std::string suffix;  // of the stored file
    uint64_t size;       // payload bytes
    std::unique_ptr<StreamedBlobFile> file;
  };
  explicit SceneUpload(const v1::SceneHeader& header) : header_(header) {}

  v1::SceneHeader header_;
  std::vector<Part> parts_;  // in payload order
  size_t part_ = 0;          // the part the next bytes go to
  uint64_t part_end_ = 0;    // payload offset where parts_[part_] ends
  uint64_t received_ = 0;
  uint64_t expected_ = 0;
  std::optional<Sha256Stream> hash_;  // texts and mesh: their address as the bytes come
};

}  // namespace radflux
