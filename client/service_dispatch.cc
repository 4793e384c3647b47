#include "client/service_dispatch.h"

#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace radflux::cli {
namespace {

constexpr std::array<std::string_view, 5> kServiceVerbs = {"submit", "watch", "result", "cancel",
                                                           "list"};
constexpr std::array<std::string_view, 5> kConnectionOptions = {"--server", "--token", "--tls-ca",
                                                                "--tls-cert", "--tls-key"};

bool TakesValue(std::string_view option) {
  for (std::string_view o : kConnectionOptions) {
    if (option == o) return true;
  }
  return false;
}

}  // namespace

bool IsServiceVerb(std::string_view verb) {
  for (std::string_view v : kServiceVerbs) {
    if (verb == v) return true;
  }
  return false;
}

std::string_view FindVerb(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string_view arg = argv[k];
    if (arg.empty() || arg[0] != '-') return arg;
    if (TakesValue(arg)) ++k;  // "--server HOST:PORT"; "--server=HOST:PORT" is one argument
  }
  return {};
}

std::string ExecServiceBinary(char** argv) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return "cannot find this executable (/proc/self/exe): " + error.message();
  const std::filesystem::path service = self.parent_path() / "radflux-service";
  argv[0] = const_cast<char*>(service.c_str());
  ::execv(service.c_str(), argv);
  return "cannot run " + service.string() + " (it implements the service verbs and is installed " +
         "next to radflux): " + std::strerror(errno);
}

}  // namespace radflux::cli
