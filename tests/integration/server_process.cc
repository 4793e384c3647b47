#include "tests/integration/server_process.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>

#include "tests/integration/radfluxd_path.h"

namespace radflux::testing {

ServerProcess::ServerProcess(const std::string& data_dir, const std::vector<std::string>& extra) {
  int out[2];
  if (pipe(out) != 0) throw std::runtime_error("pipe");
  std::vector<std::string> args = {RadfluxdPath(), "--listen", "127.0.0.1:0", "--data-dir",
                                   data_dir};
  args.insert(args.end(), extra.begin(), extra.end());
  pid_ = fork();
  if (pid_ == 0) {
    dup2(out[1], STDOUT_FILENO);
    close(out[0]);
    close(out[1]);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(out[1]);
  FILE* stream = fdopen(out[0], "r");
  char line[512];
  const std::string marker = "radfluxd listening on ";
  while (fgets(line, sizeof(line), stream)) {
    std::string text(line);
    if (text.rfind(marker, 0) == 0) {
      address_ = text.substr(marker.size());
      while (!address_.empty() && (address_.back() == '\n' || address_.back() == '\r'))
        address_.pop_back();
      break;
    }
  }
  // Keep the pipe open but drained in the background is unnecessary: the server prints
  // one line to stdout; its logs go to stderr.
  fclose(stream);
  if (address_.empty()) {
    Stop();
    throw std::runtime_error("radfluxd did not start");
  }
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0) Stop();
}

int ServerProcess::Stop() {
  if (pid_ <= 0) return -1;
  kill(pid_, SIGTERM);
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
  return status;
}

void ServerProcess::Kill() {
  if (pid_ <= 0) return;
  kill(pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
}

}  // namespace radflux::testing
