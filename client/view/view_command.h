// `radflux view`: a job's live view in the browser, a saved result's, or the server's jobs.
#pragma once

#include <string>

#include "client/service_client.h"

namespace radflux::cli {

struct ViewArgs {
  std::string target;  // a job id, a saved result (*.glb), or empty: the server's jobs
  int port = 0;        // 0: a free port
  int reconnect_seconds = 60;
};

// Serves the view of `args.target` on 127.0.0.1 until the process is stopped, printing its
// URL on stdout first. `client` is used only for job targets and the job list. Returns
// the exit code when it cannot start (one line on stderr says why).
int RunView(const ConnectionFlags& connection, const ViewArgs& args);

}  // namespace radflux::cli
