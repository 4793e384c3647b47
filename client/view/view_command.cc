#include "client/view/view_command.h"

#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "absl/strings/match.h"
#include "client/view/view_feed.h"
#include "client/view/view_server.h"

namespace radflux::cli {
namespace {

// The views of the jobs asked for so far, each fed by its own thread from first use.
class JobViews {
 public:
  JobViews(Client& client, int reconnect_seconds)
      : client_(client), reconnect_seconds_(reconnect_seconds) {}
  std::shared_ptr<ViewState> Get(const std::string& job_id) {
    std::lock_guard lock(mu_);
    std::shared_ptr<ViewState>& state = views_[job_id];
    if (!state) {
      state = std::make_shared<ViewState>();
      std::thread([this, job_id, state] {
        FeedJobView(client_, job_id, reconnect_seconds_, state.get());
      }).detach();
    }
    return state;
  }

 private:
  Client& client_;
  const int reconnect_seconds_;
  std::mutex mu_;
  std::map<std::string, std::shared_ptr<ViewState>> views_;
};

// The server's jobs (ListJobs) as the page's JSON array.
absl::StatusOr<std::string> JobList(Client& client) {
  v1::ListJobsRequest request;
  request.set_page_size(100);
  v1::ListJobsResponse response;
  const grpc::Status status = client.stub().ListJobs(client.Context().get(), request, &response);
  if (!status.ok()) return absl::UnavailableError(status.error_message());
  nlohmann::json jobs = nlohmann::json::array();
  for (const v1::Job& job : response.jobs()) {
    jobs.push_back({{"job_id", job.job_id()}, {"state", v1::JobState_Name(job.state())},
                    {"phase", v1::Phase_Name(job.phase())}, {"patches", job.patches()},
                    {"not_converged", job.has_converged() && !job.converged()},
                    {"energy_balance_off",
                     job.has_energy_balance_ok() && !job.energy_balance_ok()},
                    {"message", job.message()}});
  }
  return jobs.dump();
}

absl::StatusOr<std::string> ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(path + ": cannot open");
  std::stringstream bytes;
  bytes << in.rdbuf();
  if (bytes.str().size() < 12 || bytes.str().compare(0, 4, "glTF") != 0) {
    return absl::InvalidArgumentError(path + ": not a binary glTF (.glb) file");
  }
  return bytes.str();
}

// One line on stderr for a local failure of the view.
int ViewFailed(const absl::Status& status) {
  std::cerr << "radflux view: " << status.message() << "\n";
  return 1;
}

}  // namespace

int RunView(const ConnectionFlags& connection, const ViewArgs& args) {
  absl::StatusOr<std::string> three = FindThreeDir();
  if (!three.ok()) return ViewFailed(three.status());
  ViewRoutes routes;
  std::unique_ptr<Client> client;
  std::unique_ptr<JobViews> views;
  if (absl::EndsWith(args.target, ".glb")) {
    absl::StatusOr<std::string> glb = ReadFile(args.target);
    if (!glb.ok()) return ViewFailed(glb.status());
    routes.glb = *std::move(glb);
    routes.home = "/glb/";
  } else {
    client = std::make_unique<Client>(connection);
    views = std::make_unique<JobViews>(*client, args.reconnect_seconds);
    routes.job = [&views](const std::string& id) { return views->Get(id); };
    routes.jobs = [&client] { return JobList(*client); };
    routes.home = args.target.empty() ? "/jobs/" : "/job/" + args.target + "/";
    if (!args.target.empty()) views->Get(args.target);  // follow it before any tab opens
  }
  const absl::Status served = ServeView(routes, *three, args.port, [&](int port) {
    std::cout << "http://127.0.0.1:" << port << routes.home << std::endl;
    std::cerr << "radflux view: serving on 127.0.0.1:" << port
              << " (Ctrl-C to stop; from another machine: ssh -L " << port << ":127.0.0.1:"
              << port << " HOST)\n";
  });
  return ViewFailed(served);
}

}  // namespace radflux::cli
