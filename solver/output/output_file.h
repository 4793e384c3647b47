// Writing a whole output file at once, with errors that name the file and the reason.
// Used by every writer in solver/output so that failures read the same way.
#pragma once

#include <string>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace radflux {

// Writes `bytes` to `path` (created or truncated). `kind` names the format in messages,
// e.g. "PLY": "cannot write PLY file 'out/x.ply': No such file or directory".
absl::Status WriteOutputFile(const std::string& path, absl::string_view bytes,
                             absl::string_view kind);

}  // namespace radflux
