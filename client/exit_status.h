// How a verb ends: one line on stderr naming the verb and the problem, and an exit code
// (2 for bad input the user can fix, 1 for everything else).
#pragma once

#include <cstdio>
#include <string>

#include "absl/status/status.h"

namespace radflux::cli {

// Prints `radflux VERB: message` for a failed status and returns the exit code; 0 when ok.
inline int ReportStatus(const char* verb, const absl::Status& status) {
  if (status.ok()) return 0;
  std::fprintf(stderr, "radflux %s: %s\n", verb, std::string(status.message()).c_str());
  return status.code() == absl::StatusCode::kInvalidArgument ? 2 : 1;
}

}  // namespace radflux::cli
