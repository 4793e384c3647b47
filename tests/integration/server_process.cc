#include "tests/integration/server_process.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "tests/integration/radfluxd_path.h"

namespace radflux::testing {

ServerProcess::ServerProcess(const std::string& data_dir, const std::vector<std::string>& extra) {
  int out[2];
  if (pipe(out) != 0) throw std::runtime_error("pipe");
  std::vector<std::string> args = {RadfluxdPath(), "--listen", "127.0.0.1:0", "--data-dir",
                                   data_dir};
  args.insert(args.end(), extra.begin(), extra.end());
  // Built before fork: the child of a threaded process only calls what is safe there.
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // Warnings and errors only, unless the caller set SPDLOG_LEVEL: a failing test's output
  // then ends with its assertions, not under thousands of info lines (CI keeps a part).
  std::string quiet = "SPDLOG_LEVEL=warn";
  std::vector<char*> envp;
  for (char** e = environ; *e != nullptr; ++e) envp.push_back(*e);
  if (std::getenv("SPDLOG_LEVEL") == nullptr) envp.push_back(quiet.data());
  envp.push_back(nullptr);
  pid_ = fork();
  if (pid_ == 0) {
    dup2(out[1], STDOUT_FILENO);
    close(out[0]);
    close(out[1]);
    execve(argv[0], argv.data(), envp.data());
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
