// WatchReactor: one WatchJob stream. Sends the job's events in sequence order from the
// watcher's resume point, interleaved with the newest snapshot at the watcher's cadence;
// at most one write in flight, Finish exactly once (OK after the terminal event, or
// CANCELLED when the client goes away). Never blocks the job: it reads the hub when ready.
// It writes pre-serialized events (a raw method, see RadiosityService): every watcher sends
// the bytes the hub serialized once, not a copy of its own.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>

#include "radflux/v1/job.pb.h"
#include "server/jobs/job_hub.h"

namespace radflux {

class WatchReactor final : public grpc::ServerWriteReactor<grpc::ByteBuffer> {
 public:
  WatchReactor(std::shared_ptr<JobHub> hub, const v1::WatchJobRequest& request);

  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  // What the hub's wake-up reaches: cleared in OnDone so no wake touches a dead reactor.
  struct Link {
    std::recursive_mutex mu;  // recursive: harmless if gRPC ever runs OnDone inline
    WatchReactor* reactor = nullptr;
  };

  // Starts the next write or the Finish, if one is due and none is in flight.
  void Pump();
  bool NextMessage();   // fills message_; called with mu_ held
  bool NextSnapshot();  // fills message_ with the newest due snapshot, if any

  const std::shared_ptr<JobHub> hub_;
  const v1::WatchJobRequest request_;
  std::shared_ptr<Link> link_;
  int subscription_ = 0;
  std::mutex mu_;
  uint64_t sent_sequence_ = 0;
  int next_snapshot_iteration_ = 0;
  bool terminal_sent_ = false;  // the job's final event went out: no snapshot after it
  bool in_flight_ = false;
  bool finished_ = false;
  bool cancelled_ = false;
  int messages_sent_ = 0;     // writes started
  grpc::ByteBuffer message_;  // a serialized v1::JobEvent
};

}  // namespace radflux
