#include "client/service_dispatch.h"

#include <limits.h>
#include <string.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace radflux::cli {
namespace {

constexpr std::array<std::string_view, 6> kServiceVerbs = {"submit", "watch", "result", "cancel",
                                                           "list",   "view"};
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

bool IsSolveWithView(int argc, char** argv) {
  if (FindVerb(argc, argv) != "solve") return false;
  for (int k = 1; k < argc; ++k) {
    if (std::string_view(argv[k]) == "--view") return true;
  }
  return false;
}

const char* SiblingFor(int argc, char** argv) {
  return IsServiceVerb(FindVerb(argc, argv)) || IsSolveWithView(argc, argv) ? "radflux-service"
                                                                             : "radflux-local";
}

void ExecSibling(const char* name, char** argv) {
  char path[PATH_MAX];
  const ssize_t length = ::readlink("/proc/self/exe", path, sizeof path);
  if (length <= 0 || static_cast<size_t>(length) >= sizeof path) {
    std::fprintf(stderr, "radflux: cannot find this executable (/proc/self/exe): %s\n",
                 length < 0 ? std::strerror(errno) : "path too long");
    return;
  }
  char* slash = static_cast<char*>(::memrchr(path, '/', static_cast<size_t>(length)));
  const size_t directory = slash == nullptr ? 0 : static_cast<size_t>(slash - path) + 1;
  if (directory + std::strlen(name) >= sizeof path) {
    std::fprintf(stderr, "radflux: the path of %s next to %.*s is too long\n", name,
                 static_cast<int>(length), path);
    return;
  }
  std::strcpy(path + directory, name);
  argv[0] = path;
  ::execv(path, argv);
  std::fprintf(stderr,
               "radflux: cannot run %s (it implements this verb and is installed next to "
               "radflux): %s\n",
               path, std::strerror(errno));
}

}  // namespace radflux::cli
