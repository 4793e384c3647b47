// What import changed in a scene or left out of it, one entry per kind of fix-up: the count
// and where it first happened. Printed as one line per kind, listed in the report's JSON.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace radflux {

struct ImportFixup {
  std::string kind;     // stable key for scripts, e.g. "triangulated_non_convex"
  // What was done, in words; "{one|many}" picks by count, e.g.
  // "non-convex {face|faces} triangulated".
  std::string message;
  uint64_t count = 0;  // how many times (faces, materials, ...)
  std::string first;   // where it first happened, "file:line" (may be empty)

  // The message for this count: each "{one|many}" replaced by `one` when count is 1, else
  // by `many` ("1 material clamped", "2 materials clamped").
  std::string Text() const;
};

class ImportLog {
 public:
  // Counts one occurrence of `kind` at `where`; the first call of a kind fixes its message
  // and location.
  void Add(const std::string& kind, const std::string& message, const std::string& where,
           uint64_t count = 1);
  const std::vector<ImportFixup>& fixups() const { return fixups_; }
  bool empty() const { return fixups_.empty(); }
  // One line per kind: "import: 12 non-convex faces triangulated (first at a.obj:621)",
  // the message's number agreeing with the count (ImportFixup::Text).
  std::vector<std::string> Lines() const;

 private:
  std::vector<ImportFixup> fixups_;
};

}  // namespace radflux
