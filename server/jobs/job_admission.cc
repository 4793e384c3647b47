// JobManager's admission: an upload checked and stored, and a submit checked against the
// server's limits (patches, memory) before it becomes a job.
#include <spdlog/spdlog.h>
#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "server/jobs/job_manager.h"
#include "server/jobs/row_budget.h"
#include "server/store/disk_space.h"
#include "solver/pipeline.h"
#include "solver/scene/validation.h"
#include "wire/proto_convert.h"
#include "wire/stored_scene.h"

namespace radflux {
namespace {

// Upper bound of the patch count of subdividing with max_edge, without subdividing.
double MaxEdgePatchBound(const Scene& scene, double max_edge) {
  double bound = 0;
  for (const Face& face : scene.faces) {
    const std::vector<Vec3> polygon = FacePolygon(scene, face);
    double longest = 0;
    for (size_t k = 0; k < polygon.size(); ++k) {
      const Vec3& a = polygon[k];
      const Vec3& b = polygon[(k + 1) % polygon.size()];
      longest = std::max(longest, std::hypot(a.x - b.x, a.y - b.y, a.z - b.z));
    }
    const double per_edge = std::ceil(longest / max_edge) + 1;
    bound += per_edge * per_edge * static_cast<double>(polygon.size());
  }
  return bound;
}

}  // namespace

absl::StatusOr<v1::SceneRef> JobManager::AddScene(const v1::SceneHeader& header,
                                                  StoredScene scene) {
  const std::string sha = StoredSceneHash(scene);
  if (!header.sha256().empty() && header.sha256() != sha) {
    return absl::DataLossError(
        absl::StrCat("upload hashes to ", sha, ", not the declared ", header.sha256()));
  }
  if (scene.name.empty()) {
    scene.name = !scene.files.empty() ? scene.files[0].path
                 : scene.mesh.empty() ? "scene.obj"
                                      : "mesh";
  }
  // Checked with the default import rules; a job's own (--strict, --emit, ...) are applied
  // when it is submitted, so a scene lit only by --emit uploads without an emitter.
  absl::StatusOr<Scene> loaded = LoadStoredScene(scene, ImportOptions{});
  if (!loaded.ok()) return absl::InvalidArgumentError(std::string(loaded.status().message()));
  if (absl::Status s = ValidateScene(*loaded, /*require_emitter=*/false); !s.ok()) {
    return absl::InvalidArgumentError(s.message());
  }
  v1::SceneRef ref;
  ref.set_sha256(sha);
  ref.set_faces(loaded->faces.size());
  ref.set_materials(loaded->materials.size());
  ref.set_already_stored(store_.HasScene(sha));
  if (!ref.already_stored()) {
    if (absl::Status s = store_.PutScene(sha, scene); !s.ok()) return s;
    spdlog::info("scene {} stored ({}, {} faces)", sha.substr(0, 12), scene.name, ref.faces());
  }
  return ref;
}

absl::Status JobManager::CheckLimits(const v1::SubmitJobRequest& request) {
  absl::StatusOr<std::shared_ptr<const LoadedScene>> loaded =
      scenes_.Get(request.scene_sha256(), request.options().import_options());
  if (!loaded.ok()) return loaded.status();
  const Scene& scene = (*loaded)->scene;
  absl::StatusOr<JobOptions> options = FromProto(request.options());
  if (!options.ok()) return options.status();
  if (absl::Status s = ValidateJobOptions(*options); !s.ok()) return s;
  const int64_t max_patches = options_.max_patches;
  const auto too_many = [&](double n) {
    return absl::ResourceExhaustedError(absl::StrCat("job would mesh ", static_cast<int64_t>(n),
                                                     " patches; this server allows at most ",
                                                     max_patches, " (--max-patches)"));
  };
  if (max_patches > 0 && options->mesh.target_patches > max_patches) {
    return too_many(static_cast<double>(options->mesh.target_patches));
  }
  if (max_patches > 0 && options->mesh.max_edge > 0) {
    const double bound = MaxEdgePatchBound(scene, options->mesh.max_edge);
    if (bound > 4.0 * static_cast<double>(max_patches)) return too_many(bound);
  }
  const uint64_t patches = (*loaded)->PatchCount(JobMeshOptions(*options));
  if (absl::Status s =
          RowMemoryBudget(patches, *options, PerJobMemoryLimit(options_.max_memory)).status();
      !s.ok()) {
    return s;
  }
  return CheckDiskRoom(patches, *options);
}

absl::Status JobManager::CheckDiskRoom(uint64_t patches, const JobOptions& options) {
  // On disk a job keeps its row blocks (stored compressed), the rows it spills (at most
  // all), its checkpoint and its result: bounded by its memory estimate with its rows in
  // memory, which counts the rows twice (for cg's copy) besides mesh and solver vectors.
  JobOptions in_memory = options;
  in_memory.spill.memory_limit = 0;
  const uint64_t need = EstimateJobBytes(patches, in_memory);
  const absl::StatusOr<uint64_t> free = FreeDiskBytes(store_.data_dir());
  if (!free.ok() || need <= *free) return absl::OkStatus();
  constexpr double kMiB = 1 << 20;
  return absl::ResourceExhaustedError(absl::StrFormat(
      "job would need up to %.1f MiB of disk (%d patches: rows, checkpoint, result); the data "
      "directory %s has %.1f MiB free",
      static_cast<double>(need) / kMiB, patches, store_.data_dir(),
      static_cast<double>(*free) / kMiB));
}

}  // namespace radflux
