#include "solver/output/ply_writer.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "solver/output/export_mesh.h"
#include "solver/output/output_file.h"

namespace radflux {
namespace {

static_assert(std::endian::native == std::endian::little, "PLY writer assumes little endian");

template <typename T>
void Append(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

// `wide`: a face has more than 255 vertices (a patch with many T-junctions), so the
// vertex count of a face is written as uint32 instead of uint8.
std::string PlyHeader(size_t vertices, size_t faces, bool wide) {
  return absl::StrCat(
      "ply\nformat binary_little_endian 1.0\n",
      "comment radflux lit mesh: positions in scene units, radiosity in W/m^2,\n",
      "comment red/green/blue = tone-mapped radiance B/pi (as the PNG)\n", "element vertex ",
      vertices, "\n", "property float x\nproperty float y\nproperty float z\n",
      "property float nx\nproperty float ny\nproperty float nz\n",
      "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n",
      "property uchar red\nproperty uchar green\nproperty uchar blue\n", "element face ", faces,
      "\n", "property list ", wide ? "uint" : "uchar", " int vertex_indices\nend_header\n");
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

absl::Status WritePly(const std::string& path, const PatchMesh& mesh, const ShadingMesh& shading,
                      const std::vector<Rgb>& patch_radiosity, const ToneMapOptions& tone) {
  auto lit = BuildExportMesh(mesh, shading, patch_radiosity);
  if (!lit.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat("PLY file '", path, "': ", lit.status().message()));
  }
  size_t largest = 0;
  for (size_t i = 0; i < lit->polygons(); ++i) {
    largest = std::max<size_t>(largest, lit->polygon_first[i + 1] - lit->polygon_first[i]);
  }
  const bool wide = largest > 255;
  std::string out = PlyHeader(lit->positions.size(), lit->polygons(), wide);
  out.reserve(out.size() + lit->positions.size() * 39 + lit->polygon_vertices.size() * 5);
  for (size_t i = 0; i < lit->positions.size(); ++i) {
    AppendVertex(out, lit->positions[i], lit->normals[i], lit->radiosity[i], tone);
  }
  for (size_t i = 0; i < lit->polygons(); ++i) {
    const uint32_t count = lit->polygon_first[i + 1] - lit->polygon_first[i];
    if (wide) {
      Append(out, count);
    } else {
      Append(out, static_cast<uint8_t>(count));
    }
    for (uint32_t k = lit->polygon_first[i]; k < lit->polygon_first[i + 1]; ++k) {
      Append(out, static_cast<int32_t>(lit->polygon_vertices[k]));
    }
  }
  return WriteOutputFile(path, out, "PLY");
}

}  // namespace radflux
