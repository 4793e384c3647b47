// ServerProcess: a radfluxd child process for integration tests, on a loopback port the
// server chose itself (--listen 127.0.0.1:0, port read back from its stdout).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace radflux::testing {

class ServerProcess {
 public:
  // Starts radfluxd with --data-dir `data_dir` and `extra` flags; waits until it listens.
  ServerProcess(const std::string& data_dir, const std::vector<std::string>& extra = {});
  // SIGTERM and wait, if still running.
  ~ServerProcess();

  const std::string& address() const { return address_; }
  pid_t pid() const { return pid_; }
  // Graceful stop (SIGTERM); returns the exit status.
  int Stop();
  // kill -9, no chance to clean up.
  void Kill();

 private:
  pid_t pid_ = -1;
  std::string address_;
};

}  // namespace radflux::testing
