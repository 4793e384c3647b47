// The HTTP side of `radflux view`: one page (client/view/index.html, view.js, embedded in
// the binary), three.js from its installed files, and each job's data, served on
// 127.0.0.1 only with cpp-httplib. A job's progress reaches the page as Server-Sent Events
// (latest wins: each stream sends the newest state when it is ready for more); its
// snapshots are fetched by the page as binary, newest only.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "client/view/view_state.h"

namespace radflux::cli {

// What the server shows; each part may be empty.
struct ViewRoutes {
  // The view of a job id (started on first use; null: no such job, 404), for /job/ID/...
  std::function<std::shared_ptr<ViewState>(const std::string& job_id)> job;
  // The server's jobs as a JSON array (ListJobs), for /jobs/.
  std::function<absl::StatusOr<std::string>()> jobs;
  std::string glb;   // a saved result (GLB bytes), for /glb/
  std::string home;  // where "/" leads: "/job/ID/", "/jobs/" or "/glb/"
};

// The directory of three.js (libjs-three: build/three.min.js, examples/js/...): the
// environment's RADFLUX_THREE_DIR, else the one found at build time, else Debian's
// /usr/share/javascript/three. NOT_FOUND, naming where it looked, when none has it.
absl::StatusOr<std::string> FindThreeDir();

// Serves `routes` on 127.0.0.1:`port` (0: a free port) until the process ends; calls
// `ready` with the port once it listens. An error when it cannot listen.
absl::Status ServeView(const ViewRoutes& routes, const std::string& three_dir, int port,
                       const std::function<void(int port)>& ready);

}  // namespace radflux::cli
