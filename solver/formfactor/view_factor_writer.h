// Writing surface-to-surface view factors row by row as they are computed, in the formats
// thermal and urban tools read (issue 23). Memory: one row at a time, whatever n.
//
//   csv     header `from,NAME1,...,NAMEn`, then `NAME,F_i1,...,F_in` per surface (dense).
//   sparse  `i j F_ij dropped_i` lines, 1-based, rows ascending, columns ascending: uDALES's
//           vfsparse.inp (its readers take the first three columns). Entries F_ij < min_vf
//           are left out and their sum is `dropped_i`, the 4th column, the same on every line
//           of row i, so that sum_j F_ij (lines) + dropped_i is row i's full sum. A row with
//           no entry >= min_vf keeps its largest entry, so every row that sees anything has
//           a line (and its closure is known); a row of zeros has none.
//   view3d  View3D 3.2's text output (out=0, SaveF0): a 30-character header line
//           `radflux 3.2 0 ENCL EMIT N` (program, View3D format version, format 0, the
//           enclosure flag, the emittance flag, surface count), the areas (%g), one row of
//           n view factors per surface (%.6f), the emittances (%.3f) — the layout scripts
//           reading View3D's files expect (skip two lines, drop the last).
//   svf     (beside any of those) uDALES's svf.inp: `# sky view factors`, then
//           max(0, 1 - sum_j F_ij) per surface, one per line (%.6f).
#pragma once

#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"

namespace radflux {

enum class ViewFactorFormat { kCsv, kSparse, kView3d };

// "csv", "sparse", "view3d"; nullopt for anything else.
std::optional<ViewFactorFormat> ParseViewFactorFormat(std::string_view name);

// What every format needs to know about the surfaces before the first row.
struct ViewFactorSurfaces {
  std::vector<std::string> names;  // one per surface, output order
  std::vector<double> area;        // m^2, one per surface
  std::vector<double> emittance;   // View3D's emit value per surface, in (0, 1]
  bool enclosure = false;          // View3D header's encl flag (rows were normalised)
  bool emittances = false;         // View3D header's emit flag
};

struct ViewFactorOutput {
  ViewFactorFormat format = ViewFactorFormat::kCsv;
  std::string path;      // the view-factor file
  double min_vf = 0;     // sparse: entries below this are dropped (sum kept, see above)
  std::string svf_path;  // "" = no sky-view-factor file
};

// Writes rows 0, 1, ..., n-1 in order; Close() finishes the files.
class ViewFactorWriter {
 public:
  // Creates the files and writes their headers; errors name the file.
  static absl::StatusOr<std::unique_ptr<ViewFactorWriter>> Open(const ViewFactorOutput& output,
                                                                ViewFactorSurfaces surfaces);
  ~ViewFactorWriter();
  ViewFactorWriter(const ViewFactorWriter&) = delete;
  ViewFactorWriter& operator=(const ViewFactorWriter&) = delete;

  // The next row: F from the next surface to each of the n surfaces (row.size() == n).
  absl::Status WriteRow(std::span<const double> row);
  // Writes what follows the rows (View3D's emittances), flushes and closes; INTERNAL naming
  // the file when a write failed (disk full) or fewer than n rows were written.
  absl::Status Close();

 private:
  ViewFactorWriter(const ViewFactorOutput& output, ViewFactorSurfaces surfaces)
      : output_(output), surfaces_(std::move(surfaces)) {}
  absl::Status WriteHeader();
  void WriteSparseRow(std::span<const double> row);

  ViewFactorOutput output_;
  ViewFactorSurfaces surfaces_;
  std::string line_;  // the line being formatted, kept to reuse its buffer
  std::FILE* file_ = nullptr;
  std::FILE* svf_ = nullptr;
  size_t rows_ = 0;
};

}  // namespace radflux
