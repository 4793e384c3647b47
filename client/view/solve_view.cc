#include "client/view/solve_view.h"

#include <iostream>

#include "client/view/view_content.h"
#include "client/view/view_server.h"
#include "solver/grouped_mesh.h"
#include "wire/proto_convert.h"

namespace radflux::cli {
namespace {

constexpr std::chrono::milliseconds kInterval(100);
constexpr char kHome[] = "/job/local/";

v1::JobEvent Event(v1::JobState state, v1::Phase phase) {
  v1::JobEvent event;
  event.set_state(state);
  event.set_phase(phase);
  return event;
}

}  // namespace

bool SolveView::Due(std::chrono::steady_clock::time_point& last, bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last < kInterval) return false;
  last = now;
  return true;
}

absl::Status SolveView::Start(const Scene& scene, const JobOptions& options) {
  absl::StatusOr<std::string> three = FindThreeDir();
  if (!three.ok()) return three.status();
  absl::StatusOr<GroupedMesh> mesh = SubdivideAndGroup(scene, JobMeshOptions(options));
  if (!mesh.ok()) return mesh.status();
  clusters_ = std::move(mesh->clusters);
  state_->SetInfo(ViewInfo("local", ToProto(options), mesh->mesh.size()), MeshBytes(mesh->mesh));
  words_ = std::make_unique<JobProgress>(options.solver.tolerance);
  PublishEvent(Event(v1::JOB_STATE_RUNNING, v1::PHASE_PREPARE), *words_, state_.get());
  ViewRoutes routes;
  routes.job = [state = state_](const std::string& id) { return id == "local" ? state : nullptr; };
  routes.home = kHome;
  auto listening = std::make_shared<std::promise<absl::Status>>();
  std::future<absl::Status> started = listening->get_future();
  server_ = std::thread([routes, three = *three, port = port_, listening] {
    bool ready = false;
    const absl::Status s = ServeView(routes, three, port, [&](int bound) {
      std::cerr << "radflux solve: view at http://127.0.0.1:" << bound << kHome << "\n";
      ready = true;
      listening->set_value(absl::OkStatus());
    });
    if (!ready) listening->set_value(s);
  });
  const absl::Status s = started.get();
  if (!s.ok()) server_.join();  // ServeView returned: the thread is ending
  return s;
}

SolveView::~SolveView() {
  // A solve that failed after Start leaves the page's server running: the process is ending.
  if (server_.joinable()) server_.detach();
}

void SolveView::Phase(int64_t done, int64_t total) {
  if (!Due(last_event_, done == total)) return;
  v1::JobEvent event = Event(v1::JOB_STATE_RUNNING, v1::PHASE_ROWS);
  event.mutable_progress()->set_rows_done(done);
  event.mutable_progress()->set_rows_total(total);
  PublishEvent(event, *words_, state_.get());
}

void SolveView::Iteration(const SolveProgress& p) {
  if (Due(last_event_, false)) {
    v1::JobEvent event = Event(v1::JOB_STATE_RUNNING, v1::PHASE_SOLVE);
    event.mutable_progress()->set_iteration(p.iteration);
    event.mutable_progress()->set_residual(p.residual);
    PublishEvent(event, *words_, state_.get());
  }
  if (!p.snapshot || !Due(last_snapshot_, false)) return;
  PublishRadiosity(p.iteration,
                   clusters_.empty() ? *p.snapshot : PushDownToPatches(clusters_, *p.snapshot),
                   state_.get());
}

void SolveView::Finish(const JobResult& result, const nlohmann::json& report) {
  const std::vector<Rgb>& b = result.solve.radiosity;
  PublishRadiosity(result.solve.iterations, b, state_.get());
  v1::JobEvent event = Event(v1::JOB_STATE_SUCCEEDED, v1::PHASE_DONE);
  event.mutable_progress()->set_iteration(result.solve.iterations);
  event.mutable_progress()->set_residual(result.solve.residual);
  event.set_converged(result.solve.converged);
  PublishEvent(event, *words_, state_.get());
  absl::StatusOr<std::string> glb = GlbBytes(result.job->scene, result.job->mesh, b);
  state_->End(report.dump(), glb.ok() ? *std::move(glb) : std::string());
}

void SolveView::ServeUntilStopped() {
  std::cerr << "radflux solve: done; the view stays until Ctrl-C\n";
  server_.join();
}

}  // namespace radflux::cli
