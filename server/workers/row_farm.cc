#include "server/workers/row_farm.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <iterator>

#include "absl/strings/str_cat.h"
#include "server/workers/block_wire.h"

namespace radflux {
namespace {

constexpr std::chrono::milliseconds kLocalPoll{100};  // how often waiting threads expire leases

int64_t UnixMsIn(double seconds) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
             .count() +
         static_cast<int64_t>(seconds * 1000);
}

}  // namespace

void RowFarm::Open(const FarmJob& job, const std::vector<uint32_t>& missing, BlockSink sink) {
  std::lock_guard lock(mu_);
  jobs_[job.job_id] = std::make_unique<Job>(Job{job, LeaseTable(missing), std::move(sink), 0, {}, {}});
  cv_.notify_all();
}

FarmReport RowFarm::Close(const std::string& job_id) {
  std::unique_lock lock(mu_);
  const auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return {};
  Job* job = it->second.get();
  cv_.wait(lock, [&] { return job->sinking == 0; });  // a check or sink may use the runner's state
  FarmReport report = std::move(job->report);
  jobs_.erase(job_id);
  cv_.notify_all();
  const Stats& t = stats_;  // since the server started
  spdlog::info(
      "row farm: {} blocks built here, {} by workers ({} rows, {} wire bytes, {:.1f} bytes/row, "
      "{:.4f} s worker build per block, {:.6f} s server check per block), {} duplicates, "
      "{} leased again, {} backups built here",
      t.local_blocks, t.remote_blocks, t.remote_rows, t.wire_bytes,
      t.remote_rows ? static_cast<double>(t.wire_bytes) / static_cast<double>(t.remote_rows) : 0.0,
      t.remote_blocks ? t.remote_build_seconds / static_cast<double>(t.remote_blocks) : 0.0,
      t.remote_blocks ? t.accept_seconds / static_cast<double>(t.remote_blocks) : 0.0, t.duplicates,
      t.released, t.backups);
  if (report.remote_rows > 0 || report.rejected_blocks > 0) {
    spdlog::info(
        "job {}: verified {} of {} worker rows in {:.3f} s ({:.2f}% of the {:.3f} s the workers "
        "reported building them), {} block(s) rejected",
        job_id, report.verified_rows, report.remote_rows, report.verify_seconds,
        report.remote_build_seconds > 0
            ? 100 * report.verify_seconds / report.remote_build_seconds
            : 0.0,
        report.remote_build_seconds, report.rejected_blocks);
  }
  return report;
}

std::optional<uint32_t> RowFarm::NextLocal(const std::string& job_id,
                                           const std::atomic<bool>* stop) {
  std::unique_lock lock(mu_);
  while (true) {
    const auto it = jobs_.find(job_id);
    if (it == jobs_.end() || (stop && stop->load())) return std::nullopt;
    ExpireLocked(Clock::now());
    LeaseTable& table = it->second->table;
    if (std::optional<uint32_t> block = table.Take(LeaseTable::kLocal, {})) return block;
    if (table.AllDone()) return std::nullopt;
    if (std::optional<uint32_t> block = TakeBackupLocked(job_id, *it->second)) return block;
    cv_.wait_for(lock, kLocalPoll);
  }
}

bool RowFarm::ClaimLocal(const std::string& job_id, uint32_t block) {
  std::lock_guard lock(mu_);
  const auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return false;
  if (!it->second->table.Claim(block)) {
    ++stats_.duplicates;
    spdlog::info("job {}: row block {} built here discarded: a worker delivered it first", job_id,
                 block);
    return false;
  }
  ++stats_.local_blocks;
  return true;
}

void RowFarm::FinishBlock(const std::string& job_id, uint32_t block) {
  std::lock_guard lock(mu_);
  if (const auto it = jobs_.find(job_id); it != jobs_.end()) it->second->table.Finish(block);
  cv_.notify_all();
}

bool RowFarm::AllDone(const std::string& job_id) {
  std::lock_guard lock(mu_);
  const auto it = jobs_.find(job_id);
  return it != jobs_.end() && it->second->table.AllDone();
}

std::optional<uint32_t> RowFarm::TakeBackupLocked(const std::string& job_id, Job& job) {
  const std::optional<LeaseTable::Backup> backup = job.table.TakeBackup(Clock::now() - kBackupAfter);
  if (!backup) return std::nullopt;
  ++stats_.backups;
  const auto w = workers_.find(backup->worker);
  spdlog::warn("job {}: row block {} built here as a backup: worker {} ({}) has held it for {:.1f} s",
               job_id, backup->block, backup->worker, w == workers_.end() ? "gone" : w->second.name,
               std::chrono::duration<double>(Clock::now() - backup->leased_at).count());
  return backup->block;
}

void RowFarm::Heard(uint64_t worker) {
  std::lock_guard lock(mu_);
  const auto w = workers_.find(worker);
  if (w == workers_.end()) return;
  w->second.last_heard = Clock::now();
  if (w->second.silent) {
    w->second.silent = false;
    spdlog::info("worker {} ({}) answers again", worker, w->second.name);
  }
}

uint64_t RowFarm::AddWorker(int threads, const std::string& name) {
  std::lock_guard lock(mu_);
  const uint64_t id = next_worker_++;
  Worker& w = workers_[id];
  w.threads = std::max(1, threads);
  w.name = name;
  cv_.notify_all();
  return id;
}

void RowFarm::RemoveWorker(uint64_t worker, const std::string& reason) {
  std::lock_guard lock(mu_);
  for (auto& [job_id, job] : jobs_) {
    LogRelease(job_id, *job, job->table.Release(worker),
               absl::StrCat("worker ", worker, " ", reason));
  }
  workers_.erase(worker);
  cv_.notify_all();
}

std::optional<v1::BlockLease> RowFarm::NextLease(uint64_t worker, std::chrono::milliseconds wait) {
  std::unique_lock lock(mu_);
  const auto until = Clock::now() + wait;
  while (!shutdown_) {
    const auto w = workers_.find(worker);
    if (w == workers_.end()) return std::nullopt;
    ExpireLocked(Clock::now());
    for (auto& [job_id, job] : jobs_) {
      if (w->second.active >= w->second.threads) break;
      if (job->banned.contains(worker)) continue;
      const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                               std::chrono::duration<double>(lease_seconds_));
      const std::optional<uint32_t> block = job->table.Take(worker, deadline);
      if (!block) continue;
      const FarmJob& spec = job->spec;
      v1::BlockLease lease;
      lease.set_lease_id(next_lease_++);
      lease.set_job_id(job_id);
      lease.set_scene_sha256(spec.scene_sha256);
      *lease.mutable_options() = spec.options;
      lease.set_block_index(*block);
      lease.set_first_row(*block * spec.block_size);
      lease.set_row_count(std::min(spec.block_size, spec.patch_count - lease.first_row()));
      lease.set_deadline_unix_ms(UnixMsIn(lease_seconds_));
      lease.set_patch_count(spec.patch_count);
      w->second.issued[lease.lease_id()] =
          Issued{job_id, *block, lease.first_row(), lease.row_count(), true};
      ++w->second.active;
      return lease;
    }
    if (cv_.wait_until(lock, until) == std::cv_status::timeout) return std::nullopt;
  }
  return std::nullopt;
}

absl::Status RowFarm::CheckResult(const Issued& issued, Job& job, const v1::BlockResult& r,
                                  StoredRowBlock* rows) {
  const uint32_t patch_count = job.spec.patch_count;
  absl::StatusOr<StoredRowBlock> unpacked =
      UnpackRowBlock(r, MaxRowBlockBytes(issued.row_count, patch_count));
  if (!unpacked.ok()) return unpacked.status();
  if (job.spec.dense) return CheckDense(issued, job, *std::move(unpacked), rows);
  if (unpacked->view_factors) {
    return absl::InvalidArgumentError("a view-factor block for a form-factor job's lease");
  }
  const RowBlock& block = unpacked->block;
  absl::StatusOr<std::vector<uint32_t>> high_sum =
      CheckRowBlock(block, issued.first_row, issued.row_count, patch_count, job.spec.max_row_sum);
  if (!high_sum.ok()) return high_sum.status();
  if (job.spec.rebuild) {
    std::vector<uint32_t> sample;
    {
      std::lock_guard lock(mu_);
      sample = SampleRows(issued.first_row, issued.row_count, verify_fraction_, rng_);
    }
    std::vector<uint32_t> check;
    std::set_union(sample.begin(), sample.end(), high_sum->begin(), high_sum->end(),
                   std::back_inserter(check));
    const auto start = Clock::now();
    const absl::Status same = VerifyRows(block, check, job.spec.rebuild);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    {
      std::lock_guard lock(mu_);
      job.report.verified_rows += check.size();
      job.report.verify_seconds += seconds;
    }
    if (!same.ok()) return same;
  }
  *rows = *std::move(unpacked);
  return absl::OkStatus();
}

absl::Status RowFarm::CheckDense(const Issued& issued, Job& job, StoredRowBlock unpacked,
                                 StoredRowBlock* rows) {
  std::vector<uint32_t> sample;
  {
    std::lock_guard lock(mu_);
    sample = SampleRows(issued.first_row, issued.row_count, verify_fraction_, rng_);
  }
  const auto start = Clock::now();
  const absl::Status same =
      CheckDenseBlock(unpacked, issued.first_row, issued.row_count, *job.spec.dense, sample);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  {
    std::lock_guard lock(mu_);
    job.report.verified_rows += sample.size();
    job.report.verify_seconds += seconds;
  }
  if (!same.ok()) return same;
  *rows = std::move(unpacked);
  return absl::OkStatus();
}

void RowFarm::Reject(uint64_t worker, const Issued& issued, Job& job, const absl::Status& why) {
  std::lock_guard lock(mu_);
  const auto w = workers_.find(worker);
  const std::string who =
      absl::StrCat("worker ", worker, " (", w == workers_.end() ? "gone" : w->second.name, ")");
  spdlog::error("job {}: row block {} from {} rejected, the worker is banned from the job: {}",
                issued.job_id, issued.block, who, std::string(why.message()));
  job.banned.insert(worker);
  ++job.report.rejected_blocks;
  job.report.rejected.push_back(
      absl::StrCat(who, " block ", issued.block, ": ", why.message()));
  LogRelease(issued.job_id, job, job.table.Release(worker), who + " was banned from the job");
  cv_.notify_all();
}

void RowFarm::EndUse(Job* job) {
  if (job == nullptr) return;
  std::lock_guard lock(mu_);
  --job->sinking;
  cv_.notify_all();
}

absl::Status RowFarm::Accept(uint64_t worker, const v1::BlockResult& r) {
  Issued issued;
  Job* job = nullptr;  // kept alive until EndUse: Close waits for it
  {
    std::lock_guard lock(mu_);
    const auto w = workers_.find(worker);
    if (w == workers_.end()) return absl::FailedPreconditionError("worker is gone");
    const auto it = w->second.issued.find(r.lease_id());
    if (it == w->second.issued.end()) {
      return absl::InvalidArgumentError(
          absl::StrCat("result for lease ", r.lease_id(), ", which this worker does not hold"));
    }
    issued = it->second;
    w->second.issued.erase(it);
    if (issued.active) --w->second.active;
    cv_.notify_all();  // a thread of this worker is free again
    const auto found = jobs_.find(issued.job_id);
    if (found != jobs_.end() && !found->second->banned.contains(worker)) {
      job = found->second.get();
      ++job->sinking;
    }
  }
  const absl::Status status = AcceptFor(worker, issued, job, r);
  EndUse(job);
  return status;
}

absl::Status RowFarm::AcceptFor(uint64_t worker, const Issued& issued, Job* job,
                                const v1::BlockResult& r) {
  if (r.job_id() != issued.job_id || r.block_index() != issued.block ||
      r.first_row() != issued.first_row || r.row_count() != issued.row_count) {
    return absl::InvalidArgumentError(absl::StrCat(
        "mismatched result for lease ", r.lease_id(), ": job ", r.job_id(), " block ",
        r.block_index(), " rows ", r.first_row(), "+", r.row_count(), ", leased job ",
        issued.job_id, " block ", issued.block, " rows ", issued.first_row, "+", issued.row_count));
  }
  if (job == nullptr) return absl::OkStatus();  // out of its row phase, or banned: discard
  if (r.too_large()) {
    std::lock_guard lock(mu_);
    job->table.MakeLocalOnly(issued.block);
    spdlog::warn("job {}: row block {} too large for the wire, built on the server", issued.job_id,
                 issued.block);
    cv_.notify_all();
    return absl::OkStatus();
  }
  StoredRowBlock rows;
  const auto check_start = Clock::now();
  if (absl::Status s = CheckResult(issued, *job, r, &rows); !s.ok()) {
    Reject(worker, issued, *job, s);
    // Bytes that do not even decode: the connection itself is broken or hostile.
    return s.code() == absl::StatusCode::kDataLoss ? s : absl::OkStatus();
  }
  const double check_seconds = std::chrono::duration<double>(Clock::now() - check_start).count();
  {
    std::lock_guard lock(mu_);
    if (!job->table.Claim(issued.block)) {
      ++stats_.duplicates;
      spdlog::info("job {}: row block {} from worker {} discarded: a late duplicate", issued.job_id,
                   issued.block, worker);
      return absl::OkStatus();
    }
    ++stats_.remote_blocks;
    stats_.remote_rows += issued.row_count;
    stats_.wire_bytes += r.ByteSizeLong();
    stats_.remote_build_seconds += r.build_seconds();
    stats_.accept_seconds += check_seconds;
    job->report.remote_rows += issued.row_count;
    job->report.remote_build_seconds += r.build_seconds();
  }
  job->sink(issued.block, std::move(rows));
  std::lock_guard lock(mu_);
  job->table.Finish(issued.block);
  cv_.notify_all();
  return absl::OkStatus();
}

void RowFarm::Shutdown() {
  std::lock_guard lock(mu_);
  shutdown_ = true;
  cv_.notify_all();
}

RowFarm::Stats RowFarm::stats() {
  std::lock_guard lock(mu_);
  return stats_;
}

void RowFarm::LogRelease(const std::string& job_id, const Job& job,
                         const std::vector<uint32_t>& blocks, const std::string& why) {
  for (uint32_t b : blocks) {
    const uint32_t first = b * job.spec.block_size;
    const uint32_t last = std::min(first + job.spec.block_size, job.spec.patch_count) - 1;
    spdlog::warn("job {}: row block {} (rows {}..{}) leased again: {}", job_id, b, first, last,
                 why);
    ++stats_.released;
  }
}

void RowFarm::ExpireLocked(Clock::time_point now) {
  for (auto& [id, w] : workers_) {
    if (w.silent || now - w.last_heard < kWorkerSilence) continue;
    w.silent = true;
    const std::string why = absl::StrCat(
        "worker ", id, " (", w.name, ") stopped answering: nothing heard for ",
        std::chrono::duration_cast<std::chrono::seconds>(now - w.last_heard).count(), " s");
    spdlog::warn("{}", why);
    for (auto& [job_id, job] : jobs_) LogRelease(job_id, *job, job->table.Release(id), why);
    cv_.notify_all();
  }
  for (auto& [job_id, job] : jobs_) {
    const std::vector<uint32_t> expired = job->table.Expire(now);
    if (expired.empty()) continue;
    LogRelease(job_id, *job, expired, "its worker ran past the lease deadline");
    cv_.notify_all();
  }
}

}  // namespace radflux
