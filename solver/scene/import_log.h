// What import changed in a scene or left out of it, one entry per kind of fix-up: the count
// and where it first happened. Printed as one line per kind, listed in the report's JSON.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace radflux {

struct ImportFixup {
  std::string kind;  // stable key for scripts, e.g. "triangulated_non_convex"
  // What was done, in words; "{one|many}" picks by count, e.g.
  // "non-convex {face|faces} triangulated".
  std::string message;
  uint64_t count = 0;  // how many times (faces, materials, ...)
  std::string first;   // where it first happened, "file:line" (may be empty)
  // Kinds added with ImportLog::AddShare: a share in [0, 1] of each occurrence (e.g. how
  // much of a material's scattered light a diffuse solve leaves out), what it is a share
  // of ("{one|many}" as in `message`), and the sum and largest of the shares.
  std::string share_of{};
  double share_sum = 0, share_max = 0;

  // The message for this count: each "{one|many}" replaced by `one` when count is 1, else
  // by `many` ("1 material clamped", "2 materials clamped"); with shares, followed by
  // ": 64% of the light they scatter on average, 100% at most" (share_of after the mean;
  // for one, ": 83% of the light it scatters").
  std::string Text() const;
  // The mean of the shares (AddShare kinds; 0 for none).
  double ShareMean() const { return count > 0 ? share_sum / static_cast<double>(count) : 0; }
};

class ImportLog {
 public:
  // Counts one occurrence of `kind` at `where`; the first call of a kind fixes its message
  // and location.
  void Add(const std::string& kind, const std::string& message, const std::string& where,
           uint64_t count = 1);
  // Add (one occurrence) with its share in [0, 1] of what `share_of` names.
  void AddShare(const std::string& kind, const std::string& message, const std::string& where,
                double share, const std::string& share_of);
  const std::vector<ImportFixup>& fixups() const { return fixups_; }
  bool empty() const { return fixups_.empty(); }
  // One line per kind: "import: 12 non-convex faces triangulated (first at a.obj:621)",
  // the message's number agreeing with the count (ImportFixup::Text).
  std::vector<std::string> Lines() const;

 private:
  std::vector<ImportFixup> fixups_;
};

}  // namespace radflux
