// A scene uploaded as a bundle: the scene file and the files it names (MTL, textures, glTF
// buffers and images, MGF includes), each with its path relative to the bundle's root. The
// rules a bundle's paths follow, its content address, and reading one from disk as
// `radflux submit` sends it.
#pragma once

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace radflux {

// One file of a bundle.
struct BundleFile {
  std::string path;  // relative to the bundle's root, '/'-separated ("tex/wall.png")
  std::string data;
};

// OK when `path` may name a file of a bundle: non-empty, relative, '/'-separated, without
// an empty, '.' or '..' part, a backslash or a NUL. Otherwise INVALID_ARGUMENT naming the
// path, e.g. "bundle path '../../etc/passwd' escapes the bundle (a path must be relative,
// without '..')".
absl::Status CheckBundlePath(const std::string& path);

// CheckBundlePath for every path of `paths`, and no path given twice (INVALID_ARGUMENT
// naming the first repeated one); INVALID_ARGUMENT also for an empty list.
absl::Status CheckBundlePaths(const std::vector<std::string>& paths);

// Lowercase hex SHA-256 of "radflux-bundle-v1\n" + for each file, files[0] first and the
// others in bytewise order of their paths: path + "\n" + decimal(size) + "\n" + data. The
// order the other files come in does not change the address.
std::string BundleContentHash(const std::vector<BundleFile>& files);

// The scene file `path` and the files it names that are on disk (SceneReferences), as a
// bundle: the scene file first, the others in the order named, paths relative to the
// deepest folder that holds them all. NOT_FOUND when `path` cannot be read; the loader's
// error for an MGF file whose includes do not load.
absl::StatusOr<std::vector<BundleFile>> ReadSceneBundle(const std::string& path);

}  // namespace radflux
