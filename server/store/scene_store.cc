// JobStore's scenes: content-addressed scene files under scenes/, their rows in the
// database, and which principals own each (see job_store.h).
#include <spdlog/spdlog.h>

#include <filesystem>

#include "absl/strings/str_cat.h"
#include "server/store/blob_file.h"
#include "server/store/job_store.h"
#include "server/store/sqlite_statement.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;
using store_sql::SqlError;
using store_sql::Statement;

}  // namespace

bool JobStore::HasScene(const std::string& sha256) {
  std::lock_guard lock(mu_);
  Statement st(db_, "SELECT 1 FROM scenes WHERE sha256 = ?");
  st.Bind(1, sha256);
  return st.ok() && st.Step() == SQLITE_ROW;
}

absl::StatusOr<std::unique_ptr<SceneUpload>> JobStore::StartUpload(
    const v1::SceneHeader& header) {
  return SceneUpload::Start((fs::path(data_dir_) / "scenes").string(), header);
}

absl::Status JobStore::PutScene(const std::string& sha256, const std::string& name,
                                SceneUpload& upload) {
  const std::string base = (fs::path(data_dir_) / "scenes" / sha256).string();
  if (absl::Status s = upload.Commit(base); !s.ok()) return s;
  std::lock_guard lock(mu_);
  Statement st(db_,
               "INSERT OR IGNORE INTO scenes(sha256, name, created_ms) VALUES(?, ?, "
               "CAST((julianday('now') - 2440587.5) * 86400000 AS INTEGER))");
  st.Bind(1, sha256);
  st.Bind(2, name);
  if (!st.ok() || st.Step() != SQLITE_DONE) return SqlError(db_, "a scene");
  return absl::OkStatus();
}

absl::StatusOr<StoredScene> JobStore::GetBundle(const std::string& base, const std::string& name) {
  absl::StatusOr<std::string> index = ReadBlobFile(base + ".files.rfb");
  if (!index.ok()) return index.status();
  v1::SceneHeader header;
  if (!header.ParseFromString(*index)) return absl::DataLossError(base + ".files.rfb: corrupt");
  absl::StatusOr<std::vector<BundleFile>> files = ReadBundleBlob(base + ".bundle.rfb", header);
  if (!files.ok()) return files.status();
  StoredScene scene;
  scene.name = name;
  scene.files = *std::move(files);
  return scene;
}

absl::StatusOr<StoredScene> JobStore::ReadSceneFiles(const std::string& base,
                                                     const std::string& name) {
  if (std::error_code ec; fs::exists(base + ".files.rfb", ec)) return GetBundle(base, name);
  StoredScene scene;
  scene.name = name;
  if (std::error_code ec; fs::exists(base + ".mesh.rfb", ec)) {
    absl::StatusOr<std::string> mesh = ReadBlobFile(base + ".mesh.rfb");
    if (!mesh.ok()) return mesh.status();
    scene.mesh = *std::move(mesh);
    return scene;
  }
  absl::StatusOr<std::string> obj = ReadBlobFile(base + ".obj.rfb");
  if (!obj.ok()) return obj.status();
  absl::StatusOr<std::string> mtl = ReadBlobFile(base + ".mtl.rfb");
  if (!mtl.ok()) return mtl.status();
  scene.obj = *std::move(obj);
  scene.mtl = *std::move(mtl);
  return scene;
}

absl::StatusOr<StoredScene> JobStore::GetScene(const std::string& sha256) {
  std::string name;
  {
    std::lock_guard lock(mu_);
    Statement st(db_, "SELECT name FROM scenes WHERE sha256 = ?");
    st.Bind(1, sha256);
    if (!st.ok() || st.Step() != SQLITE_ROW) {
      return absl::NotFoundError(
          absl::StrCat("no scene with sha256 ", sha256, "; upload it first"));
    }
    name = st.Column(0);
  }
  const std::string base = (fs::path(data_dir_) / "scenes" / sha256).string();
  absl::StatusOr<StoredScene> scene = ReadSceneFiles(base, name);
  if (scene.ok()) return scene;
  // Files lost or failing their check: the scene is forgotten (its owners stay), so that
  // HasScene says no and an upload of the same bytes writes it again.
  spdlog::error("stored scene {}: {}; marked missing", sha256,
                std::string(scene.status().message()));
  std::lock_guard lock(mu_);
  Statement st(db_, "DELETE FROM scenes WHERE sha256 = ?");
  st.Bind(1, sha256);
  if (!st.ok() || st.Step() != SQLITE_DONE) return SqlError(db_, "a corrupt scene's row");
  return absl::DataLossError(absl::StrCat("stored scene ", sha256,
                                          " is lost or corrupt on the server; upload it again"));
}

absl::Status JobStore::AddSceneOwner(const std::string& sha256, const std::string& owner) {
  std::lock_guard lock(mu_);
  Statement st(db_, "INSERT OR IGNORE INTO scene_owners(sha256, owner) VALUES(?, ?)");
  st.Bind(1, sha256);
  st.Bind(2, owner);
  if (!st.ok() || st.Step() != SQLITE_DONE) return SqlError(db_, "a scene's owner");
  return absl::OkStatus();
}

bool JobStore::SceneOwnedBy(const std::string& sha256, const std::string& owner) {
  std::lock_guard lock(mu_);
  Statement st(db_, "SELECT 1 FROM scene_owners WHERE sha256 = ? AND owner = ?");
  st.Bind(1, sha256);
  st.Bind(2, owner);
  return st.ok() && st.Step() == SQLITE_ROW;
}

}  // namespace radflux
