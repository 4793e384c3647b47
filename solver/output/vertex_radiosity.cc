#include "solver/output/vertex_radiosity.h"

#include "absl/strings/str_cat.h"

namespace radflux {

absl::StatusOr<std::vector<Rgb>> VertexRadiosity(const PatchMesh& mesh,
                                                 const std::vector<Rgb>& patch_radiosity) {
  if (patch_radiosity.size() != mesh.size()) {
    return absl::InvalidArgumentError(absl::StrCat("radiosity has ", patch_radiosity.size(),
                                                   " values for ", mesh.size(), " patches"));
  }
  std::vector<Rgb> sum(mesh.positions.size(), Rgb{});
  std::vector<double> weight(mesh.positions.size(), 0.0);
  for (size_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    for (int k = 0; k < patch.VertexCount(); ++k) {
      const uint32_t vertex = patch.v[k];
      if (vertex >= sum.size()) {
        return absl::InvalidArgumentError(
            absl::StrCat("patch ", p, " uses vertex ", vertex, " of ", sum.size()));
      }
      for (int b = 0; b < kBands; ++b) sum[vertex][b] += patch.area * patch_radiosity[p][b];
      weight[vertex] += patch.area;
    }
  }
  for (size_t i = 0; i < sum.size(); ++i) {
    if (weight[i] <= 0) continue;
    for (double& value : sum[i]) value /= weight[i];
  }
  return sum;
}

std::vector<Vec3> VertexNormals(const PatchMesh& mesh) {
  std::vector<Vec3> normals(mesh.positions.size(), Vec3{0, 0, 1});
  for (const Patch& patch : mesh.patches) {
    for (int k = 0; k < patch.VertexCount(); ++k) {
      if (patch.v[k] < normals.size()) normals[patch.v[k]] = patch.normal;
    }
  }
  return normals;
}

}  // namespace radflux
