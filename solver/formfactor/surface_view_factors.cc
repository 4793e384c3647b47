#include "solver/formfactor/surface_view_factors.h"

#include <cstdio>
#include <map>

#include "solver/output/output_file.h"

namespace radflux {
namespace {

std::string SurfaceName(const Scene& scene, uint32_t face, SurfaceGrouping by) {
  switch (by) {
    case SurfaceGrouping::kObject:
      return scene.objects[scene.faces[face].object];
    case SurfaceGrouping::kGroup:
      return scene.groups[scene.faces[face].group];
    case SurfaceGrouping::kFace:
      return "face" + std::to_string(face);
  }
  return {};
}

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

SurfaceViewFactors AggregateViewFactors(const Scene& scene, const PatchMesh& mesh,
                                        const CsrMatrix& rows, SurfaceGrouping by) {
  SurfaceViewFactors out;
  std::map<std::string, size_t> index;
  std::vector<size_t> surface_of(mesh.size());
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const std::string name = SurfaceName(scene, mesh.patches[p].face, by);
    auto [it, inserted] = index.try_emplace(name, out.names.size());
    if (inserted) out.names.push_back(name);
    surface_of[p] = it->second;
  }
  const size_t s = out.names.size();
  out.factor.assign(s, std::vector<double>(s, 0.0));
  std::vector<double> area(s, 0.0);
  for (uint32_t i = 0; i < mesh.size(); ++i) {
    area[surface_of[i]] += mesh.patches[i].area;
    const auto cols = rows.RowCols(i);
    const auto vals = rows.RowValues(i);
    for (size_t k = 0; k < cols.size(); ++k) {
      out.factor[surface_of[i]][surface_of[cols[k]]] += mesh.patches[i].area * vals[k];
    }
  }
  for (size_t a = 0; a < s; ++a) {
    for (double& f : out.factor[a]) f /= area[a];
  }
  return out;
}

absl::Status WriteViewFactorsCsv(const std::string& path, const SurfaceViewFactors& factors) {
  std::string text = "from";
  for (const std::string& name : factors.names) text += "," + CsvField(name);
  text += "\n";
  char number[32];
  for (size_t a = 0; a < factors.names.size(); ++a) {
    text += CsvField(factors.names[a]);
    for (double f : factors.factor[a]) {
      std::snprintf(number, sizeof number, ",%.9g", f);
      text += number;
    }
    text += "\n";
  }
  return WriteOutputFile(path, text, "view-factor CSV");
}

}  // namespace radflux
