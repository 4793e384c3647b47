// RowFarm: where a job's row phase meets the worker nodes. The job runner opens the phase
// with the blocks still to build; its own threads and every connected worker take blocks
// from the same LeaseTable. A remote lease has a deadline; a block whose worker leaves,
// is dropped, or runs past the deadline is leased again (logged with the block). The first
// result of a block is stored, a late duplicate is discarded. Workers are not trusted: a
// result is checked (lease, job, block, rows, SHA-256, a decoded size bounded by the lease,
// then every offset, column and value: row_check.h) and a random sample of its rows, plus
// every row whose sum is above its limit (FarmJob::max_row_sum), is recomputed here and
// must match bit for bit. A block that fails is dropped and leased again, its worker
// banned from the job (logged, and counted in the job's FarmReport); a result that does not
// even decode also drops the worker's connection. Stragglers cost seconds, not the lease:
// a worker not heard from (Heard: any message, heartbeats every second) for kWorkerSilence
// has its blocks leased again, and once no block is pending the server's threads build the
// blocks still out with workers for kBackupAfter as backups (MapReduce's backup tasks): the
// first result of a block is kept, the other dropped. Thread-safe.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "radflux/v1/worker.pb.h"
#include "server/store/stored_codec.h"
#include "server/workers/lease_table.h"
#include "server/workers/row_check.h"

namespace radflux {

// What a worker needs to build the blocks of a job.
struct FarmJob {
  std::string job_id;
  std::string scene_sha256;
  v1::SolveOptions options;
  uint32_t patch_count = 0;
  uint32_t block_size = 0;
  RowRebuilder rebuild;  // the server's own rows, to verify workers' (empty: verify none)
  // The sum each row may honestly reach (RowContext::MaxRowSum); rows above it are always
  // recomputed (empty: 1).
  std::function<double(uint32_t row)> max_row_sum;
  // Set for a view-factor job: its blocks carry SurfaceRowPlan's values (StoredRowBlock::
  // view_factors), checked by CheckDenseBlock (rebuild and max_row_sum are not used).
  std::optional<DenseRows> dense;
};

// What the row farm saw of one job's workers, for the job's report and logs.
struct FarmReport {
  uint64_t remote_rows = 0;           // rows accepted from workers
  uint64_t verified_rows = 0;         // rows of workers recomputed here and compared
  double verify_seconds = 0;          // server time recomputing them, s
  double remote_build_seconds = 0;    // the accepted blocks' build time as workers reported
  uint64_t rejected_blocks = 0;       // blocks dropped: malformed or not matching
  std::vector<std::string> rejected;  // "worker ID (NAME) block B: why", one per rejection
};

// The default fraction of each worker block's rows recomputed on the server (at least one
// row per block): 1 row of a 64-row block.
inline constexpr double kDefaultVerifyFraction = 0.015;
// A worker silent this long is taken as stopped: its blocks are leased again.
inline constexpr std::chrono::seconds kWorkerSilence{5};
// A block out with a worker this long is built on the server too, once none is pending.
inline constexpr std::chrono::seconds kBackupAfter{2};

class RowFarm {
 public:
  using Clock = std::chrono::steady_clock;
  // Receives the first result of each block (on the thread that delivered it).
  using BlockSink = std::function<void(uint32_t block, StoredRowBlock rows)>;

  // `lease_seconds`: how long a worker may hold a block before it is leased again;
  // `verify_fraction`: the part of each worker block's rows recomputed here (SampleRows).
  explicit RowFarm(double lease_seconds = 300, double verify_fraction = kDefaultVerifyFraction)
      : lease_seconds_(lease_seconds), verify_fraction_(verify_fraction) {}

  // --- the job runner's side ---
  // Opens a job's row phase over `missing` blocks; `sink` gets every block built remotely.
  void Open(const FarmJob& job, const std::vector<uint32_t>& missing, BlockSink sink);
  // Ends the phase (done or stopped): later results for the job are discarded. What the
  // farm saw of the job's workers.
  FarmReport Close(const std::string& job_id);
  // The next block for a server thread. Waits while every remaining block is out with a
  // worker (expiring overdue leases meanwhile); nullopt when all are done or *stop is set.
  std::optional<uint32_t> NextLocal(const std::string& job_id, const std::atomic<bool>* stop);
  // Claims a block a server thread built: true = store it; false = a worker was first.
  bool ClaimLocal(const std::string& job_id, uint32_t block);
  // After the claimed block was handed to the store.
  void FinishBlock(const std::string& job_id, uint32_t block);
  bool AllDone(const std::string& job_id);

  // --- the worker service's side ---
  uint64_t AddWorker(int threads, const std::string& name);
  // The worker sent something (a heartbeat or a result): it is alive.
  void Heard(uint64_t worker);
  // Releases the worker's leases (each logged with `reason`) and forgets it.
  void RemoveWorker(uint64_t worker, const std::string& reason);
  // A lease for the worker when it has a free thread and a block is pending; waits up to
  // `wait` for one (nullopt on timeout or Shutdown).
  std::optional<v1::BlockLease> NextLease(uint64_t worker, std::chrono::milliseconds wait);
  // Checks and stores a worker's result. OK also for a discarded duplicate, a result of a
  // job that is no longer in its row phase or that bans the worker, and a rejected block
  // (the worker is then banned from the job); an error means: drop this worker.
  absl::Status Accept(uint64_t worker, const v1::BlockResult& result);
  // Wakes every waiter (shutdown); NextLease returns nullopt from then on.
  void Shutdown();

  // Counters for logs and benches.
  struct Stats {
    uint64_t remote_blocks = 0, local_blocks = 0, duplicates = 0, released = 0, backups = 0;
    uint64_t wire_bytes = 0, remote_rows = 0;
    double remote_build_seconds = 0;  // as the workers reported them
    double accept_seconds = 0;        // server time checking and decoding remote blocks
  };
  Stats stats();

 private:
  struct Job {
    FarmJob spec;
    LeaseTable table;
    BlockSink sink;
    int sinking = 0;               // results being checked or handed to `sink` (Close waits)
    std::set<uint64_t> banned;     // workers that sent a bad block: no more leases, results dropped
    FarmReport report;
  };
  struct Issued {  // a lease as handed to a worker
    std::string job_id;
    uint32_t block = 0, first_row = 0, row_count = 0;
    bool active = true;  // still counted against the worker's threads
  };
  struct Worker {
    int threads = 1;
    std::string name;
    int active = 0;
    std::map<uint64_t, Issued> issued;  // by lease id
    Clock::time_point last_heard = Clock::now();
    bool silent = false;  // not heard from for kWorkerSilence: its leases were released
  };
  absl::Status CheckResult(const Issued& issued, Job& job, const v1::BlockResult& result,
                           StoredRowBlock* rows);
  // CheckResult of a view-factor block (FarmJob::dense): CheckDenseBlock with a sample.
  absl::Status CheckDense(const Issued& issued, Job& job, StoredRowBlock unpacked,
                          StoredRowBlock* rows);
  // Drops a bad block: bans `worker` from the job, releases its blocks, logs and counts it.
  void Reject(uint64_t worker, const Issued& issued, Job& job, const absl::Status& why);
  // Accept's checks and storing, with `job` (null: discard) held open for it.
  absl::Status AcceptFor(uint64_t worker, const Issued& issued, Job* job,
                         const v1::BlockResult& result);
  // After a result of `job` (which may be null) is done with: Close may go on.
  void EndUse(Job* job);
  void LogRelease(const std::string& job_id, const Job& job, const std::vector<uint32_t>& blocks,
                  const std::string& why);
  // Leases past their deadline, and those of workers silent for kWorkerSilence, go back.
  void ExpireLocked(Clock::time_point now);
  // A block still out with a worker for kBackupAfter, for a server thread to build too.
  std::optional<uint32_t> TakeBackupLocked(const std::string& job_id, Job& job);

  const double lease_seconds_;
  const double verify_fraction_;
  std::mutex mu_;
  std::condition_variable cv_;  // notified on every state change
  std::map<std::string, std::unique_ptr<Job>> jobs_;
  std::map<uint64_t, Worker> workers_;
  uint64_t next_worker_ = 1;
  uint64_t next_lease_ = 1;
  bool shutdown_ = false;
  Stats stats_;
  std::mt19937_64 rng_{std::random_device{}()};  // which rows to verify: unknown to workers
};

}  // namespace radflux
