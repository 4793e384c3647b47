#include "solver/scene/mgf_interpreter.h"

#include <algorithm>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

namespace radflux {
namespace {

absl::Status Invalid(const std::string& what) { return absl::InvalidArgumentError(what); }

// "path:line: message" for an error without a location.
absl::Status Locate(const std::string& path, int line, const absl::Status& status) {
  return absl::InvalidArgumentError(absl::StrCat(path, ":", line, ": ", status.message()));
}

// `name` as seen from the file `from`: joined to its folder unless absolute, normalised.
std::string IncludePath(const std::string& from, const std::string& name) {
  std::filesystem::path p(name);
  if (p.is_relative()) p = std::filesystem::path(from).parent_path() / p;
  return p.lexically_normal().generic_string();
}

bool IsSkippedEntity(std::string_view e) { return e == "ies" || e == "ir"; }

}  // namespace

MgfInterpreter::MgfInterpreter(const ImportOptions& options, const MgfLimits& limits,
                               const MgfFileReader& reader, Scene& scene)
    : options_(options), limits_(limits), reader_(reader), scene_(scene) {
  object_ = InternName(scene_.objects, object_index_, "");
}

absl::Status MgfInterpreter::RunMain(const std::string& path, const std::string& text) {
  if (options_.curve_segments < 3 || options_.curve_segments > limits_.max_curve_segments) {
    return Invalid(absl::StrCat(path, ": curve segments ", options_.curve_segments, " outside [3, ",
                                limits_.max_curve_segments, "]"));
  }
  scene_.source = path;
  scene_.files = {path};
  FileRun run{path, 0, TokenizeMgf(text), 0};
  include_stack_ = {std::filesystem::path(path).lexically_normal().generic_string()};
  return RunFile(run, 0, false);
}

absl::Status MgfInterpreter::RunFile(FileRun& run, int depth, bool include_frame) {
  const size_t objects_base = object_path_.size();
  for (;;) {
    for (size_t pc = 0; pc < run.statements.size();) {
      if (absl::Status s = Execute(run, pc, depth); !s.ok()) return s;
    }
    if (xf_.size() > run.xf_base) {
      return Invalid(absl::StrCat(xf_.back().path, ":", xf_.back().line,
                                  ": xf transform is never closed (no matching 'xf' line)"));
    }
    if (object_path_.size() > objects_base) object_path_.resize(objects_base);  // left open
    object_ = InternName(scene_.objects, object_index_, absl::StrJoin(object_path_, "."));
    if (!include_frame) return absl::OkStatus();
    const XfFrame& include = xf_.back();
    if (absl::Status tick = Tick(include.path, include.line); !tick.ok()) return tick;
    if (!StepXf()) return absl::OkStatus();
  }
}

absl::Status MgfInterpreter::Execute(FileRun& run, size_t& pc, int depth) {
  const MgfStatement& s = run.statements[pc];
  const std::string& e = s.words[0];
  if (absl::Status tick = Tick(run.path, s.line); !tick.ok()) return tick;
  if (e == "i") {
    ++pc;
    return Include(run, s, depth);
  }
  absl::Status status;
  if (e == "xf" && s.words.size() == 1) {
    if (xf_.size() <= run.xf_base) {
      return Locate(run.path, s.line,
                    Invalid("'xf' ends a transform but none is open in this file"));
    }
    pc = StepXf() ? xf_.back().start_pc : pc + 1;
    return absl::OkStatus();
  }
  ++pc;
  if (e == "xf") {
    status = PushXf({s.words.begin() + 1, s.words.end()}, pc, run.path, s.line);
  } else if (MgfMaterialContext::Handles(e)) {
    status = materials_.Apply(s.words);
  } else if (e == "o") {
    status = Object(s.words);
  } else if (e == "v" || e == "p" || e == "n") {
    status = VertexStatement(s.words);
  } else if (e == "f") {
    status = Face(run, s);
  } else if (e == "fh") {
    status = FaceWithHoles(run, s);
  } else if (e == "sph" || e == "cyl" || e == "cone" || e == "ring" || e == "torus" ||
             e == "prism") {
    status = Primitive(run, s);
  } else if (IsSkippedEntity(e)) {
    scene_.import_log.Add(
        absl::StrCat("mgf_skipped_", e),
        absl::StrCat("MGF '", e, "' {entity|entities} skipped (no use in a diffuse solve)"),
        absl::StrCat(run.path, ":", s.line));
  } else {
    scene_.import_log.Add("mgf_unknown_entity", "unknown MGF {entity|entities} skipped",
                          absl::StrCat(run.path, ":", s.line, " ('", e.substr(0, 32), "')"));
  }
  return status.ok() ? status : Locate(run.path, s.line, status);
}

absl::Status MgfInterpreter::Tick(const std::string& path, int line) {
  if (++statements_ <= limits_.max_statements) return absl::OkStatus();
  return Locate(path, line,
                Invalid(absl::StrCat("more than ", limits_.max_statements,
                                     " statements to run (xf array too large?)")));
}

absl::Status MgfInterpreter::Include(const FileRun& run, const MgfStatement& s, int depth) {
  auto fail = [&](const std::string& what) { return Locate(run.path, s.line, Invalid(what)); };
  if (s.words.size() < 2) return fail("'i' needs a file name");
  const std::string path = IncludePath(run.path, s.words[1]);
  if (depth + 1 > limits_.max_include_depth) {
    return fail(absl::StrCat("includes nested deeper than ", limits_.max_include_depth));
  }
  if (std::find(include_stack_.begin(), include_stack_.end(), path) != include_stack_.end()) {
    return fail(
        absl::StrCat("include cycle: ", absl::StrJoin(include_stack_, " -> "), " -> ", path));
  }
  absl::StatusOr<std::string> text = reader_(path);
  if (!text.ok())
    return fail(absl::StrCat("cannot include '", path, "': ", text.status().message()));
  auto known = std::find(scene_.files.begin(), scene_.files.end(), path);
  const uint32_t index = static_cast<uint32_t>(known - scene_.files.begin());
  if (known == scene_.files.end()) scene_.files.push_back(path);
  const bool has_xf = s.words.size() > 2;
  if (has_xf) {
    if (absl::Status st = PushXf({s.words.begin() + 2, s.words.end()}, 0, run.path, s.line);
        !st.ok()) {
      return Locate(run.path, s.line, st);
    }
  }
  FileRun inner{path, index, TokenizeMgf(*text), xf_.size()};
  include_stack_.push_back(path);
  absl::Status status = RunFile(inner, depth + 1, has_xf);
  include_stack_.pop_back();
  return status;
}

absl::Status MgfInterpreter::PushXf(const std::vector<std::string>& args, size_t start_pc,
                                    const std::string& path, int line) {
  absl::StatusOr<XfProgram> program = ParseXfProgram(args);
  if (!program.ok()) return program.status();
  XfFrame frame{*std::move(program), {}, {}, start_pc, path, line};
  frame.indices.assign(frame.program.array_counts.size(), 0);
  frame.total = frame.program.Evaluate(frame.indices).Then(Transform());
  xf_.push_back(std::move(frame));
  ++epoch_;
  if (xf_.back().program.array_counts.empty()) return absl::OkStatus();
  if (object_path_.size() >= limits_.max_object_depth) {
    return Invalid(absl::StrCat("objects nested deeper than ", limits_.max_object_depth,
                                " (each xf array element is an object)"));
  }
  object_path_.emplace_back();
  NameArrayElement();
  return absl::OkStatus();
}

void MgfInterpreter::NameArrayElement() {
  if (object_path_.empty()) object_path_.emplace_back();  // the body closed it: reopen
  object_path_.back() = absl::StrCat("a", absl::StrJoin(xf_.back().indices, "."));
  object_ = InternName(scene_.objects, object_index_, absl::StrJoin(object_path_, "."));
}

bool MgfInterpreter::StepXf() {
  XfFrame& frame = xf_.back();
  ++epoch_;
  const std::vector<long long>& counts = frame.program.array_counts;
  size_t d = counts.size();
  while (d-- > 0) {
    if (++frame.indices[d] < counts[d]) break;
    frame.indices[d] = 0;
  }
  if (d == static_cast<size_t>(-1)) {
    if (!counts.empty() && !object_path_.empty()) {  // leave the array's element object
      object_path_.pop_back();
      object_ = InternName(scene_.objects, object_index_, absl::StrJoin(object_path_, "."));
    }
    xf_.pop_back();
    return false;
  }
  const Affine enclosing = xf_.size() > 1 ? xf_[xf_.size() - 2].total : Affine();
  frame.total = frame.program.Evaluate(frame.indices).Then(enclosing);
  NameArrayElement();
  return true;
}

const Affine& MgfInterpreter::Transform() const {
  static const Affine kIdentity;
  return xf_.empty() ? kIdentity : xf_.back().total;
}

absl::Status MgfInterpreter::Object(const std::vector<std::string>& words) {
  if (words.size() > 2) return Invalid("'o' takes at most one name");
  if (words.size() == 2) {
    if (object_path_.size() >= limits_.max_object_depth) {
      return Invalid(absl::StrCat("objects nested deeper than ", limits_.max_object_depth,
                                  " (an 'o' without its closing 'o'?)"));
    }
    object_path_.push_back(words[1]);
  } else if (object_path_.empty()) {
    return Invalid("'o' ends an object but none is open");
  } else {
    object_path_.pop_back();
  }
  object_ = InternName(scene_.objects, object_index_, absl::StrJoin(object_path_, "."));
  return absl::OkStatus();
}

}  // namespace radflux
