// radflux: the command-line entry point. It only dispatches: the verb decides which sibling
// executable this process becomes (client/service_dispatch.h).
#include "client/service_dispatch.h"

int main(int argc, char** argv) {
  radflux::cli::ExecSibling(radflux::cli::SiblingFor(argc, argv), argv);
  return 2;
}
