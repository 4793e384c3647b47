#include "client/view/view_server.h"

#include <httplib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "client/view/view_assets.h"

namespace radflux::cli {
namespace {

namespace fs = std::filesystem;

// A stream with nothing new sends a comment this often (and so notices a closed tab).
constexpr std::chrono::seconds kKeepAlive(5);

// An event stream holds one of the server's threads while its tab is open: room for dozens
// of tabs beside the page's other requests.
constexpr size_t kThreads = 64;

// The three.js files the page loads, by the name it asks for: path under the three dir.
const std::pair<const char*, const char*> kThreeFiles[] = {
    {"three.min.js", "build/three.min.js"},
    {"OrbitControls.js", "examples/js/controls/OrbitControls.js"},
    {"GLTFLoader.js", "examples/js/loaders/GLTFLoader.js"},
};

void ServeThree(httplib::Server& server, const std::string& three_dir) {
  for (const auto& [name, path] : kThreeFiles) {
    const std::string file = (fs::path(three_dir) / path).string();
    server.Get(absl::StrCat("/static/", name), [file](const httplib::Request&, httplib::Response& res) {
      std::stringstream bytes;
      bytes << std::ifstream(file, std::ios::binary).rdbuf();
      res.set_content(bytes.str(), "text/javascript");
    });
  }
}

void ServeSnapshot(const ViewState& state, httplib::Response& res) {
  std::shared_ptr<const ViewSnapshot> s = state.Snapshot();
  res.set_header("Cache-Control", "no-store");
  if (!s) {
    res.status = 204;
    return;
  }
  res.set_header("X-Iteration", std::to_string(s->iteration));
  res.set_header("X-Serial", std::to_string(s->serial));
  res.set_header("X-Exposure-Scale", absl::StrCat(s->exposure_scale));
  res.set_content(s->half_rgb, "application/octet-stream");
}

// Server-Sent Events of `state`: each message the newest state (ViewState::Message), sent
// when the tab has taken the previous one; versions in between are skipped.
void ServeEvents(std::shared_ptr<ViewState> state, httplib::Response& res) {
  res.set_header("Cache-Control", "no-store");
  auto cursor = std::make_shared<size_t>(0);
  auto version = std::make_shared<uint64_t>(0);
  res.set_chunked_content_provider(
      "text/event-stream", [state, cursor, version](size_t, httplib::DataSink& sink) {
        const uint64_t now = state->WaitNewer(*version, kKeepAlive);
        if (now == *version) {
          static constexpr char kComment[] = ": keep-alive\n\n";
          return sink.write(kComment, sizeof kComment - 1);
        }
        *version = now;
        const std::string message = absl::StrCat("data: ", state->Message(cursor.get()), "\n\n");
        return sink.write(message.data(), message.size());
      });
}

void ServeJob(const ViewRoutes& routes, httplib::Server& server) {
  server.Get(R"(/job/([A-Za-z0-9_-]+)/)", [&routes](const httplib::Request& req,
                                                     httplib::Response& res) {
    if (!routes.job(req.matches[1])) return void(res.status = 404);
    res.set_content(kViewIndexHtml, "text/html");
  });
  server.Get(R"(/job/([A-Za-z0-9_-]+)/(info|mesh|events|snapshot|report|result\.glb))",
             [&routes](const httplib::Request& req, httplib::Response& res) {
               std::shared_ptr<ViewState> state = routes.job(req.matches[1]);
               if (!state) return void(res.status = 404);
               const std::string part = req.matches[2];
               if (part == "info") return res.set_content(state->info(), "application/json");
               if (part == "mesh") return res.set_content(state->mesh(), "application/octet-stream");
               if (part == "events") return ServeEvents(state, res);
               if (part == "snapshot") return ServeSnapshot(*state, res);
               if (part == "report") return res.set_content(state->report(), "application/json");
               res.set_header("Content-Disposition",
                              absl::StrCat("attachment; filename=\"", req.matches[1].str(), ".glb\""));
               res.set_content(state->glb(), "model/gltf-binary");
             });
}

void ServeJobList(const ViewRoutes& routes, httplib::Server& server) {
  server.Get("/jobs/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(kViewIndexHtml, "text/html");
  });
  server.Get("/api/jobs", [&routes](const httplib::Request&, httplib::Response& res) {
    absl::StatusOr<std::string> jobs = routes.jobs();
    if (!jobs.ok()) {
      res.status = 502;
      return res.set_content(std::string(jobs.status().message()), "text/plain");
    }
    res.set_content(*jobs, "application/json");
  });
}

}  // namespace

absl::StatusOr<std::string> FindThreeDir() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("RADFLUX_THREE_DIR")) candidates.push_back(env);
  candidates.push_back(RADFLUX_THREE_DIR);
  candidates.push_back("/usr/share/javascript/three");
  for (const std::string& dir : candidates) {
    bool complete = true;
    for (const auto& [name, path] : kThreeFiles) complete = complete && fs::exists(fs::path(dir) / path);
    if (complete) return dir;
  }
  return absl::NotFoundError(absl::StrCat("three.js not found (looked in $RADFLUX_THREE_DIR, ",
                                          RADFLUX_THREE_DIR,
                                          ", /usr/share/javascript/three): install libjs-three"));
}

absl::Status ServeView(const ViewRoutes& routes, const std::string& three_dir, int port,
                       const std::function<void(int port)>& ready) {
  httplib::Server server;
  server.new_task_queue = [] { return new httplib::ThreadPool(kThreads); };
  server.Get("/", [&routes](const httplib::Request&, httplib::Response& res) {
    res.set_redirect(routes.home);
  });
  server.Get("/static/view.js", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(kViewJs, "text/javascript");
  });
  ServeThree(server, three_dir);
  if (routes.job) ServeJob(routes, server);
  if (routes.jobs) ServeJobList(routes, server);
  if (!routes.glb.empty()) {
    server.Get("/glb/", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(kViewIndexHtml, "text/html");
    });
    server.Get("/glb/result.glb", [&routes](const httplib::Request&, httplib::Response& res) {
      res.set_content(routes.glb, "model/gltf-binary");
    });
  }
  const int bound = port == 0 ? server.bind_to_any_port("127.0.0.1")
                              : (server.bind_to_port("127.0.0.1", port) ? port : -1);
  if (bound < 0) return absl::UnavailableError(absl::StrCat("cannot listen on 127.0.0.1:", port));
  ready(bound);
  if (!server.listen_after_bind()) return absl::InternalError("the view's HTTP server stopped");
  return absl::OkStatus();
}

}  // namespace radflux::cli
