#include "solver/output/export_mesh.h"

#include "solver/output/vertex_radiosity.h"

namespace radflux {

absl::StatusOr<ExportMesh> BuildExportMesh(const PatchMesh& mesh, const ShadingMesh& shading,
                                           const std::vector<Rgb>& patch_radiosity) {
  auto radiosity = WeldedVertexRadiosity(mesh, shading, patch_radiosity);
  if (!radiosity.ok()) return radiosity.status();
  ExportMesh m;
  m.radiosity = *std::move(radiosity);
  m.normals = shading.normals;
  m.positions.reserve(shading.size());
  for (uint32_t rep : shading.representative) m.positions.push_back(mesh.positions[rep]);
  m.polygon_first.reserve(mesh.size() + 1);
  m.polygon_first.push_back(0);
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const std::vector<uint32_t> outline = PatchOutline(mesh, shading, p);
    m.polygon_vertices.insert(m.polygon_vertices.end(), outline.begin(), outline.end());
    m.polygon_first.push_back(static_cast<uint32_t>(m.polygon_vertices.size()));
  }
  return m;
}

std::vector<uint32_t> TriangulateExportMesh(ExportMesh& m) {
  std::vector<uint32_t> indices;
  indices.reserve(m.polygon_vertices.size() * 2);
  for (size_t i = 0; i < m.polygons(); ++i) {
    const uint32_t* v = m.polygon_vertices.data() + m.polygon_first[i];
    const size_t n = m.polygon_first[i + 1] - m.polygon_first[i];
    if (n == 3) {
      indices.insert(indices.end(), {v[0], v[1], v[2]});
    } else if (n == 4) {
      indices.insert(indices.end(), {v[0], v[1], v[3], v[2], v[3], v[1]});
    } else {
      Vec3 position, normal;
      Rgb b{};
      for (size_t k = 0; k < n; ++k) {
        position += m.positions[v[k]] / static_cast<double>(n);
        normal += m.normals[v[k]];
        for (int band = 0; band < kBands; ++band) b[band] += m.radiosity[v[k]][band] / n;
      }
      const auto centre = static_cast<uint32_t>(m.positions.size());
      m.positions.push_back(position);
      m.normals.push_back(Normalize(normal));
      m.radiosity.push_back(b);
      for (size_t k = 0; k < n; ++k) indices.insert(indices.end(), {centre, v[k], v[(k + 1) % n]});
    }
  }
  return indices;
}

}  // namespace radflux
