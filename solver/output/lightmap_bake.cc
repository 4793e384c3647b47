#include "solver/output/lightmap_bake.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace radflux {
namespace {

// Writes the triangle (texel coordinates p, radiosity values b) into the texels whose
// centres it covers, marking them in `covered`.
void RasterizeTriangle(const std::array<Point2, 3>& p, const std::array<Rgb, 3>& b, Image& image,
                       std::vector<uint8_t>& covered) {
  const double area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
  if (!(std::abs(area) > 0)) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x, p[1].x, p[2].x}))));
  const int x1 = std::min(image.width - 1, static_cast<int>(std::max({p[0].x, p[1].x, p[2].x})));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y, p[1].y, p[2].y}))));
  const int y1 = std::min(image.height - 1, static_cast<int>(std::max({p[0].y, p[1].y, p[2].y})));
  const double tolerance = -1e-9 * std::abs(area);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Point2 c{x + 0.5, y + 0.5};
      std::array<double, 3> w;
      for (int k = 0; k < 3; ++k) {
        const Point2& a = p[(k + 1) % 3];
        const Point2& d = p[(k + 2) % 3];
        w[k] = ((d.x - a.x) * (c.y - a.y) - (c.x - a.x) * (d.y - a.y)) / area;
      }
      if (w[0] < tolerance || w[1] < tolerance || w[2] < tolerance) continue;
      float* texel = image.Pixel(x, y);
      for (int band = 0; band < kBands; ++band) {
        const double radiosity = w[0] * b[0][band] + w[1] * b[1][band] + w[2] * b[2][band];
        texel[band] = static_cast<float>(std::max(0.0, radiosity) / std::numbers::pi);
      }
      covered[static_cast<size_t>(y) * image.width + x] = 1;
    }
  }
}

// One dilation pass over the chart's rectangle; returns whether a texel was filled.
bool DilateOnce(const LightmapChart& chart, Image& image, std::vector<uint8_t>& covered) {
  std::vector<std::pair<int, int>> filled;
  for (int y = chart.y; y < chart.y + chart.height; ++y) {
    for (int x = chart.x; x < chart.x + chart.width; ++x) {
      if (covered[static_cast<size_t>(y) * image.width + x]) continue;
      Rgb sum{};
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < chart.x || ny < chart.y || nx >= chart.x + chart.width ||
              ny >= chart.y + chart.height ||
              covered[static_cast<size_t>(ny) * image.width + nx] != 1) {
            continue;
          }
          for (int band = 0; band < kBands; ++band) sum[band] += image.Pixel(nx, ny)[band];
          ++count;
        }
      }
      if (count == 0) continue;
      for (int band = 0; band < kBands; ++band)
        image.Pixel(x, y)[band] = static_cast<float>(sum[band] / count);
      filled.emplace_back(x, y);
    }
  }
  // Marked after the pass, so that a pass grows the chart by one texel only.
  for (const auto& [x, y] : filled) covered[static_cast<size_t>(y) * image.width + x] = 1;
  return !filled.empty();
}

}  // namespace

Image BakeLightmap(const PatchMesh& mesh, const LightmapAtlas& atlas,
                   const std::vector<Rgb>& vertex_radiosity) {
  Image image(atlas.size, atlas.size);
  std::vector<uint8_t> covered(static_cast<size_t>(atlas.size) * atlas.size, 0);
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    const LightmapChart& chart = atlas.charts[atlas.chart_of_face[patch.face]];
    const int corners[2][3] = {{0, 1, 3}, {2, 3, 1}};
    for (int t = 0; t < (patch.IsTriangle() ? 1 : 2); ++t) {
      std::array<Point2, 3> texel;
      std::array<Rgb, 3> b;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = patch.v[patch.IsTriangle() ? k : corners[t][k]];
        texel[k] = atlas.Texel(chart, mesh.positions[v]);
        b[k] = vertex_radiosity[v];
      }
      RasterizeTriangle(texel, b, image, covered);
    }
  }
  for (const LightmapChart& chart : atlas.charts) {
    for (int pass = 0; pass <= atlas.gutter && DilateOnce(chart, image, covered); ++pass) {
    }
  }
  return image;
}

}  // namespace radflux
