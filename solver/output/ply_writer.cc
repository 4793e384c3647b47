#include "solver/output/ply_writer.h"

#include <bit>
#include <cstring>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "solver/output/output_file.h"
#include "solver/output/vertex_radiosity.h"

namespace radflux {
namespace {

static_assert(std::endian::native == std::endian::little, "PLY writer assumes little endian");

template <typename T>
void Append(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

std::string PlyHeader(size_t vertices, size_t faces) {
  return absl::StrCat(
      "ply\nformat binary_little_endian 1.0\n",
      "comment radflux lit mesh: positions in scene units, radiosity in W/m^2,\n",
      "comment red/green/blue = tone-mapped radiance B/pi (as the PNG)\n", "element vertex ",
      vertices, "\n", "property float x\nproperty float y\nproperty float z\n",
      "property float nx\nproperty float ny\nproperty float nz\n",
      "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n",
      "property uchar red\nproperty uchar green\nproperty uchar blue\n", "element face ", faces,
      "\n", "property list uchar int vertex_indices\nend_header\n");
}

void AppendVertex(std::string& out, const Vec3& position, const Vec3& normal, const Rgb& b,
                  const ToneMapOptions& tone) {
  for (int i = 0; i < 3; ++i) Append(out, static_cast<float>(position[i]));
  for (int i = 0; i < 3; ++i) Append(out, static_cast<float>(normal[i]));
  for (double value : b) Append(out, static_cast<float>(value));
  const Rgb radiance = {b[0] / std::numbers::pi, b[1] / std::numbers::pi, b[2] / std::numbers::pi};
  for (uint8_t byte : ToneMapBytes(radiance, tone)) Append(out, byte);
}

}  // namespace

absl::Status WritePly(const std::string& path, const PatchMesh& mesh,
                      const std::vector<Rgb>& patch_radiosity, const ToneMapOptions& tone) {
  auto vertex_radiosity = VertexRadiosity(mesh, patch_radiosity);
  if (!vertex_radiosity.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat("PLY file '", path, "': ", vertex_radiosity.status().message()));
  }
  const std::vector<Vec3> normals = VertexNormals(mesh);
  std::string out = PlyHeader(mesh.positions.size(), mesh.size());
  out.reserve(out.size() + mesh.positions.size() * 39 + mesh.size() * 17);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    AppendVertex(out, mesh.positions[i], normals[i], (*vertex_radiosity)[i], tone);
  }
  for (const Patch& patch : mesh.patches) {
    Append(out, static_cast<uint8_t>(patch.VertexCount()));
    for (int k = 0; k < patch.VertexCount(); ++k) Append(out, static_cast<int32_t>(patch.v[k]));
  }
  return WriteOutputFile(path, out, "PLY");
}

}  // namespace radflux
