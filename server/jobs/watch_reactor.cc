#include "server/jobs/watch_reactor.h"

#include <spdlog/spdlog.h>

#include "server/jobs/cpu_time.h"
#include "wire/proto_convert.h"

namespace radflux {

WatchReactor::WatchReactor(std::shared_ptr<JobHub> hub, const v1::WatchJobRequest& request)
    : hub_(std::move(hub)), request_(request), link_(std::make_shared<Link>()) {
  sent_sequence_ = request.after_sequence();
  // Resuming after the job's final event: the watcher has seen it all, snapshots included.
  terminal_sent_ = hub_->closed() && sent_sequence_ >= hub_->last_sequence();
  link_->reactor = this;
  subscription_ = hub_->Subscribe([link = link_] {
    std::lock_guard lock(link->mu);
    if (link->reactor) link->reactor->Pump();
  });
  Pump();
}

namespace {

// A slice of `part` without a copy: the slice holds a reference until gRPC has sent it.
grpc::Slice SharedSlice(const EventWire& part) {
  auto* owner = new EventWire(part);
  return grpc::Slice(
      const_cast<char*>((*owner)->data()), (*owner)->size(),
      [](void* p) { delete static_cast<EventWire*>(p); }, owner);
}
}  // namespace

bool WatchReactor::NextMessage() {
  HubEvent event;
  if (hub_->NextEvent(sent_sequence_, &event)) {
    // The newest unsent snapshot goes out just before the job's final event, never after
    // it: the final event stays the last thing a watcher sees.
    if (IsTerminal(event.state) && NextSnapshot()) return true;
    sent_sequence_ = event.sequence;
    terminal_sent_ = terminal_sent_ || IsTerminal(event.state);
    grpc::Slice slice = SharedSlice(event.wire);
    message_ = grpc::ByteBuffer(&slice, 1);
    return true;
  }
  return !terminal_sent_ && NextSnapshot();
}

bool WatchReactor::NextSnapshot() {
  const int every = request_.snapshot_every();
  SnapshotData snapshot;
  if (every <= 0 || !hub_->NewestSnapshot(next_snapshot_iteration_, &snapshot)) return false;
  next_snapshot_iteration_ = (snapshot.iteration / every + 1) * every;
  // This watcher's header, then the shared snapshot field: protobuf parses two encodings
  // one after the other as one message with the fields of both.
  v1::JobEvent header;
  header.set_sequence(sent_sequence_);
  header.set_job_id(request_.job_id());
  header.set_state(v1::JOB_STATE_RUNNING);
  header.set_phase(v1::PHASE_SOLVE);
  const std::vector<int> bands(request_.bands().begin(), request_.bands().end());
  const grpc::Slice parts[] = {
      grpc::Slice(header.SerializeAsString()),
      SharedSlice(hub_->EncodedSnapshot(snapshot, bands, request_.snapshot_format()))};
  message_ = grpc::ByteBuffer(parts, 2);
  return true;
}

void WatchReactor::Pump() {
  std::unique_lock lock(mu_);
  if (in_flight_ || finished_) return;
  if (cancelled_) {
    finished_ = true;
    lock.unlock();
    Finish(grpc::Status::CANCELLED);
    return;
  }
  const bool closed = hub_->closed();  // read first: a closed hub has all its events
  if (NextMessage()) {
    in_flight_ = true;
    ++messages_sent_;
    lock.unlock();
    StartWrite(&message_);
    return;
  }
  if (closed) {
    finished_ = true;
    lock.unlock();
    Finish(grpc::Status::OK);
  }
}

void WatchReactor::OnWriteDone(bool ok) {
  {
    std::lock_guard lock(mu_);
    in_flight_ = false;
    if (!ok) cancelled_ = true;
  }
  Pump();
}

void WatchReactor::OnCancel() {
  {
    std::lock_guard lock(mu_);
    cancelled_ = true;
  }
  Pump();
}

void WatchReactor::OnDone() {
  // With the process's clock: the end of what a watcher costs (bench/watcher_cost.sh).
  spdlog::debug("job {}: watch ended after {} messages, process cpu clock {:.2f}",
                request_.job_id(), messages_sent_, CpuMs(CLOCK_PROCESS_CPUTIME_ID));
  {
    std::lock_guard lock(link_->mu);
    link_->reactor = nullptr;
  }
  hub_->Unsubscribe(subscription_);
  delete this;
}

}  // namespace radflux
