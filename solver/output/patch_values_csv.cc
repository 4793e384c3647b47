#include "solver/output/patch_values_csv.h"

#include <cstdio>
#include <fstream>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "solver/output/output_file.h"

namespace radflux {
namespace {

std::string QuoteCsv(const std::string& field) {
  if (field.find_first_of(",\"\n\r") == std::string::npos) return field;
  std::string quoted = "\"";
  for (char c : field) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

// Splits one CSV line into fields, honouring "quoted, fields" with "" for a quote.
absl::StatusOr<std::vector<std::string>> SplitCsv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (quoted) return absl::InvalidArgumentError("unterminated quote");
  return fields;
}

absl::StatusOr<PatchValue> ParseRow(const std::string& line) {
  auto fields = SplitCsv(line);
  if (!fields.ok()) return fields.status();
  if (fields->size() != 10) {
    return absl::InvalidArgumentError(absl::StrCat("expected 10 fields, found ", fields->size()));
  }
  const std::vector<std::string>& f = *fields;
  PatchValue row;
  row.object = f[2];
  double c[3];
  const bool ok = absl::SimpleAtoi(f[0], &row.patch) && absl::SimpleAtoi(f[1], &row.face) &&
                  absl::SimpleAtod(f[3], &row.area) && absl::SimpleAtod(f[4], &c[0]) &&
                  absl::SimpleAtod(f[5], &c[1]) && absl::SimpleAtod(f[6], &c[2]) &&
                  absl::SimpleAtod(f[7], &row.radiosity[0]) &&
                  absl::SimpleAtod(f[8], &row.radiosity[1]) &&
                  absl::SimpleAtod(f[9], &row.radiosity[2]);
  if (!ok) return absl::InvalidArgumentError("a number does not parse");
  row.centroid = {c[0], c[1], c[2]};
  return row;
}

}  // namespace

absl::Status WritePatchValuesCsv(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                                 const std::vector<Rgb>& radiosity) {
  if (radiosity.size() != mesh.size()) {
    return absl::InvalidArgumentError(absl::StrCat("CSV file '", path, "': ", radiosity.size(),
                                                   " values for ", mesh.size(), " patches"));
  }
  std::string out = absl::StrCat(kPatchValuesCsvHeader, "\n");
  for (size_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    if (patch.face >= scene.faces.size()) {
      return absl::InvalidArgumentError(absl::StrCat("CSV file '", path, "': patch ", p,
                                                     " has face ", patch.face, " not in scene"));
    }
    const uint32_t object = scene.faces[patch.face].object;
    const std::string name = object < scene.objects.size() ? scene.objects[object] : "";
    char numbers[160];
    std::snprintf(numbers, sizeof(numbers), "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", patch.area,
                  patch.centroid.x, patch.centroid.y, patch.centroid.z, radiosity[p][0],
                  radiosity[p][1], radiosity[p][2]);
    absl::StrAppend(&out, p, ",", patch.face, ",", QuoteCsv(name), ",", numbers, "\n");
  }
  return WriteOutputFile(path, out, "CSV");
}

absl::StatusOr<std::vector<PatchValue>> ReadPatchValuesCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot open CSV file '", path, "'"));
  std::string line;
  if (!std::getline(in, line) || line != kPatchValuesCsvHeader) {
    return absl::InvalidArgumentError(
        absl::StrCat(path, ":1: expected header '", kPatchValuesCsvHeader, "'"));
  }
  std::vector<PatchValue> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    auto row = ParseRow(line);
    if (!row.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat(path, ":", number, ": ", row.status().message()));
    }
    rows.push_back(std::move(*row));
  }
  return rows;
}

}  // namespace radflux
