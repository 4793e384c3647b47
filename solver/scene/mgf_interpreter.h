// The MGF statement interpreter behind mgf_loader.h: runs a file's statements against the
// vertex, material, object and transform contexts, following includes and replaying xf
// arrays, and appends the faces it makes to a Scene.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "absl/status/status.h"
#include "solver/scene/mgf_loader.h"
#include "solver/scene/mgf_material.h"
#include "solver/scene/mgf_primitives.h"
#include "solver/scene/mgf_tokenizer.h"
#include "solver/scene/mgf_transform.h"

namespace radflux {

class MgfInterpreter {
 public:
  // Faces go to `scene`, which must outlive the interpreter.
  MgfInterpreter(const ImportOptions& options, const MgfLimits& limits, const MgfFileReader& reader,
                 Scene& scene);

  // Runs the main file `text` named `path`. Error: one "file:line: ..." line.
  absl::Status RunMain(const std::string& path, const std::string& text);

 private:
  struct FileRun {
    std::string path;
    uint32_t file_index = 0;  // into Scene::files
    std::vector<MgfStatement> statements;
    size_t xf_base = 0;  // transform depth when the file started (its own frames lie above)
  };
  struct XfFrame {
    XfProgram program;               // the parsed arguments
    std::vector<long long> indices;  // the current element of each array
    Affine total;                    // this frame then every enclosing one
    size_t start_pc = 0;             // where an array element starts again
    std::string path;                // where the xf (or i) statement is
    int line = 0;
  };
  struct Vertex {
    Vec3 p, n;           // as written (untransformed)
    uint64_t epoch = 0;  // transform epoch of `index` (0: none)
    uint32_t index = 0;  // its transformed copy in Scene::positions
  };

  absl::Status RunFile(FileRun& run, int depth, bool include_frame);
  absl::Status Execute(FileRun& run, size_t& pc, int depth);
  // Counts one statement (or one array element of an include) against the limit.
  absl::Status Tick(const std::string& path, int line);
  absl::Status Include(const FileRun& run, const MgfStatement& s, int depth);
  absl::Status PushXf(const std::vector<std::string>& args, size_t start_pc,
                      const std::string& path, int line);
  // Advances the top frame's array; true when it starts another element, false when popped.
  bool StepXf();
  // Names the object in force after the innermost xf array's current element, as MGF's
  // standard parser does: "a" and its indices joined by '.' ("a3", "a1.2"), one level
  // below the objects open when the xf began (so "room.a3", "room.a3.chair").
  void NameArrayElement();
  absl::Status Object(const std::vector<std::string>& words);
  absl::Status VertexStatement(const std::vector<std::string>& words);
  absl::StatusOr<Vertex*> FindVertex(const std::string& name);
  absl::Status Face(const FileRun& run, const MgfStatement& s);
  absl::Status FaceWithHoles(const FileRun& run, const MgfStatement& s);
  absl::Status Primitive(const FileRun& run, const MgfStatement& s);
  absl::StatusOr<MgfMesh> PrimitiveMesh(const std::vector<std::string>& words);
  // Appends a face over scene positions (reversed when the transform mirrors).
  absl::Status AddFace(std::vector<uint32_t> vertices, const FileRun& run, int line);
  uint32_t ScenePoint(Vertex& v);
  const Affine& Transform() const;

  const ImportOptions& options_;
  const MgfLimits& limits_;
  const MgfFileReader& reader_;
  Scene& scene_;
  MgfMaterialContext materials_;
  std::unordered_map<std::string, Vertex> vertices_;
  Vertex unnamed_vertex_;
  Vertex* vertex_ = &unnamed_vertex_;  // the vertex p and n set
  std::vector<XfFrame> xf_;
  uint64_t epoch_ = 1;  // changes whenever the transform in force does
  std::vector<std::string> object_path_;
  std::map<std::string, uint32_t> object_index_;
  uint32_t object_ = 0;  // index of the object in force in Scene::objects
  std::vector<std::string> include_stack_;
  uint64_t statements_ = 0;
};

}  // namespace radflux
