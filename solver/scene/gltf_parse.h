// tinygltf behind one call: bytes of a .gltf or .glb in, a parsed model or one error line out.
// File access is ours, not tinygltf's defaults: external files are read only from the
// scene's own directory and below, or from a bundle of files in memory (no ".." component,
// no home-directory or shell expansion, no search of the working directory), at most
// kMaxGltfExternalBytes each from disk; images are not decoded (an image file's bytes are
// kept in Image::image; an image in a bufferView keeps only its view index).
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "absl/status/statusor.h"
#include "tiny_gltf.h"

namespace radflux {

// Largest external buffer or image file read.
inline constexpr uint64_t kMaxGltfExternalBytes = uint64_t{1} << 32;

// Deepest nesting of JSON arrays and objects accepted (glTF itself needs about 8; extras
// may nest more).
inline constexpr int kMaxGltfJsonDepth = 64;

// Whether the '/'-separated `path` has a ".." component (such paths are never read).
bool HasParentStep(const std::string& path);

// Parses `data` (GLB when it starts with the "glTF" magic, glTF JSON otherwise). External
// files (buffer and image URIs) come from `files` when it is given (keyed by the URI's path,
// URL-decoded, relative to the glTF file), else from disk relative to `base_dir`; with
// neither ("" and null) a buffer in an external file is an error. INVALID_ARGUMENT "<name>: cannot
// parse glTF: ..." on one line for anything tinygltf refuses (tinygltf's exceptions included), for
// JSON nested deeper than kMaxGltfJsonDepth, and for a file that requires an extension radflux does
// not read.
absl::StatusOr<tinygltf::Model> ParseGltf(const std::string& data, const std::string& name,
                                          const std::string& base_dir,
                                          const std::map<std::string, std::string>* files);

}  // namespace radflux
