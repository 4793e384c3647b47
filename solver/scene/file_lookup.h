// Finding a file a scene names on disk as the user's tools would: MTL files written on
// Windows name `textures\KAMEN.JPG` for `textures/kamen.JPG`. One lookup for the loaders and
// for `radflux submit` (which sends the files a scene names), so both find the same file.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "absl/status/statusor.h"

namespace radflux {

// The file `name` (relative to the folder `dir`, '\' read as '/'; an absolute `name` is
// looked up as it is): the exact path when it is a regular file, else the one whose path
// parts match case-insensitively (the first in directory order when several do); nullopt
// when there is none.
std::optional<std::string> FindFile(const std::string& dir, const std::string& name);

// The bytes of the file FindFile(dir, name) finds; NOT_FOUND "no such file" or "cannot open
// the file" otherwise.
absl::StatusOr<std::string> ReadFoundFile(const std::string& dir, const std::string& name);

// The same lookup among files in memory (an upload's bundle, keyed by '/'-separated path):
// the bytes of `path`, else of the first key that matches it ignoring case; null when none.
const std::string* FindInFiles(const std::map<std::string, std::string>& files,
                               const std::string& path);

}  // namespace radflux
