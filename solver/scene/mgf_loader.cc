#include "solver/scene/mgf_loader.h"

#include <fstream>
#include <sstream>
#include <utility>

#include "absl/strings/str_cat.h"
#include "solver/scene/mgf_interpreter.h"

namespace radflux {
namespace {

// The whole of the file `path`, or NOT_FOUND.
absl::StatusOr<std::string> ReadDiskFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError("cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

absl::StatusOr<Scene> LoadMgfText(const std::string& text, const std::string& name,
                                  const ImportOptions& options, const MgfFileReader& reader,
                                  const MgfLimits& limits) {
  Scene scene;
  MgfInterpreter interpreter(options, limits, reader, scene);
  if (absl::Status status = interpreter.RunMain(name, text); !status.ok()) return status;
  return scene;
}

absl::StatusOr<Scene> LoadMgfFile(const std::string& path, const ImportOptions& options) {
  absl::StatusOr<std::string> text = ReadDiskFile(path);
  if (!text.ok()) return absl::InvalidArgumentError(absl::StrCat(path, ": cannot open the file"));
  return LoadMgfText(*text, path, options, ReadDiskFile);
}

MgfFileReader MgfReaderFromMap(std::map<std::string, std::string> files) {
  return [files = std::move(files)](const std::string& path) -> absl::StatusOr<std::string> {
    auto it = files.find(path);
    if (it == files.end()) return absl::NotFoundError("no such file");
    return it->second;
  };
}

}  // namespace radflux
