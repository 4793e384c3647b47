#include "solver/formfactor/surface_view_factors.h"

#include <map>

namespace radflux {
namespace {

constexpr size_t kNoSurface = ~size_t{0};

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

// The surface of each patch (kNoSurface on obstruction faces); fills out.names/emittance.
std::vector<size_t> NumberSurfaces(const Scene& scene, const PatchMesh& mesh, SurfaceGrouping by,
                                   SurfaceViewFactors& out) {
  std::map<std::string, size_t> index;
  std::vector<size_t> surface_of(mesh.size(), kNoSurface);
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Face& face = scene.faces[mesh.patches[p].face];
    if (face.obstruction) continue;
    const std::string name = SurfaceName(scene, mesh.patches[p].face, by);
    auto [it, inserted] = index.try_emplace(name, out.names.size());
    if (inserted) {
      out.names.push_back(name);
      out.emittance.push_back(1 - scene.materials[face.material].reflectance[0]);
    }
    surface_of[p] = it->second;
  }
  return surface_of;
}

}  // namespace

SurfaceViewFactors AggregateViewFactors(const Scene& scene, const PatchMesh& mesh,
                                        const CsrMatrix& rows, SurfaceGrouping by) {
  SurfaceViewFactors out;
  const std::vector<size_t> surface_of = NumberSurfaces(scene, mesh, by, out);
  const size_t s = out.names.size();
  out.factor.assign(s, std::vector<double>(s, 0.0));
  out.area.assign(s, 0.0);
  for (uint32_t i = 0; i < mesh.size(); ++i) {
    if (surface_of[i] == kNoSurface) continue;
    const double area = mesh.patches[i].area * mesh.patches[i].opacity;  // what it sends from
    out.area[surface_of[i]] += area;
    const auto cols = rows.RowCols(i);
    const auto vals = rows.RowValues(i);
    for (size_t k = 0; k < cols.size(); ++k) {
      if (surface_of[cols[k]] == kNoSurface) continue;
      out.factor[surface_of[i]][surface_of[cols[k]]] += area * vals[k];
    }
  }
  for (size_t a = 0; a < s; ++a) {
    for (double& f : out.factor[a]) f /= out.area[a];
  }
  return out;
}

}  // namespace radflux
