#include "solver/scene/texture_image.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

using Polygon = std::vector<TexCoord>;

// The part of `polygon` where coordinate `axis` is >= `bound` (`keep_above`) or <= it
// (Sutherland-Hodgman against one axis-aligned line).
Polygon Clip(const Polygon& polygon, int axis, double bound, bool keep_above) {
  Polygon out;
  const auto inside = [&](const TexCoord& p) {
    return keep_above ? p[axis] >= bound : p[axis] <= bound;
  };
  for (size_t k = 0; k < polygon.size(); ++k) {
    const TexCoord& a = polygon[k];
    const TexCoord& b = polygon[(k + 1) % polygon.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      const double t = (bound - a[axis]) / (b[axis] - a[axis]);
      TexCoord p{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
      p[axis] = bound;
      out.push_back(p);
    }
  }
  return out;
}

double Area(const Polygon& p) {
  double twice = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    const TexCoord& a = p[k];
    const TexCoord& b = p[(k + 1) % p.size()];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return std::abs(twice) / 2;
}

// Whether `p` is convex: every corner turns the same way (straight corners allowed).
bool Convex(const Polygon& p) {
  bool left = false, right = false;
  for (size_t k = 0; k < p.size(); ++k) {
    const TexCoord& a = p[k];
    const TexCoord& b = p[(k + 1) % p.size()];
    const TexCoord& c = p[(k + 2) % p.size()];
    const double turn = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
    left = left || turn > 0;
    right = right || turn < 0;
  }
  return !(left && right);
}

// The x-extent of polygon `p` on the line y = h, or nullopt when no side reaches it.
std::optional<std::pair<double, double>> SpanAt(const Polygon& p, double h) {
  std::optional<std::pair<double, double>> span;
  const auto add = [&](double x) {
    span = span ? std::make_pair(std::min(span->first, x), std::max(span->second, x))
                : std::make_pair(x, x);
  };
  for (size_t k = 0; k < p.size(); ++k) {
    const TexCoord& a = p[k];
    const TexCoord& b = p[(k + 1) % p.size()];
    if (std::min(a[1], b[1]) > h || std::max(a[1], b[1]) < h) continue;
    if (a[1] == b[1]) {
      add(a[0]);
      add(b[0]);
    } else {
      add(a[0] + (h - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
    }
  }
  return span;
}

// Euclidean remainder: the texel index of cell `i` in an image `n` texels wide.
// The texel index (0..n-1) that texel cell i of an axis of n texels shows under `wrap`.
int Wrap(long long i, int n, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::kClampToEdge:
      return static_cast<int>(std::clamp<long long>(i, 0, n - 1));
    case TextureWrap::kMirroredRepeat: {
      const long long m = ((i % (2LL * n)) + 2LL * n) % (2LL * n);
      return static_cast<int>(m < n ? m : 2LL * n - 1 - m);
    }
    case TextureWrap::kRepeat:
      break;
  }
  return static_cast<int>(((i % n) + n) % n);
}

std::array<double, 4> WholeImageMean(const TextureImage& image) {
  std::array<double, 4> sum{};
  for (const auto& t : image.texels) {
    for (int c = 0; c < 4; ++c) sum[c] += t[c];
  }
  for (double& s : sum) s /= static_cast<double>(image.texels.size());
  return sum;
}

// The bounds of `p` in texels when it is a rectangle with axis-aligned sides (four corners,
// two x and two y values: most quads of a texture atlas), else nullopt.
std::optional<std::array<double, 4>> AlignedRectangle(const Polygon& p) {
  if (p.size() != 4) return std::nullopt;
  const auto [x0, x1] = std::minmax({p[0][0], p[1][0], p[2][0], p[3][0]});
  const auto [y0, y1] = std::minmax({p[0][1], p[1][1], p[2][1], p[3][1]});
  for (const TexCoord& c : p) {
    if ((c[0] != x0 && c[0] != x1) || (c[1] != y0 && c[1] != y1)) return std::nullopt;
  }
  for (size_t k = 0; k < 4; ++k) {  // sides alternate between vertical and horizontal
    const TexCoord& a = p[k];
    const TexCoord& b = p[(k + 1) % 4];
    if ((a[0] != b[0]) == (a[1] != b[1])) return std::nullopt;
  }
  return std::array<double, 4>{x0, x1, y0, y1};
}

// Length of [a, b] inside [i, i + 1].
double Overlap(double a, double b, double i) {
  return std::max(0.0, std::min(b, i + 1) - std::max(a, i));
}

// The texel cells floor(lo), floor(lo) + 1, ... below hi along one axis of n texels: the
// texel each shows under `wrap`, and its overlap with [a, b]. Worked out once per axis, so
// that a rectangle's texels cost a multiply-add each (Lost Empire's 112,499 atlas quads
// spent 65% of a solve in the wrapping and flooring per texel).
struct AxisCells {
  std::vector<size_t> texel;
  std::vector<double> overlap;
};
AxisCells CellsAlong(double lo, double hi, double a, double b, int n, TextureWrap wrap) {
  AxisCells cells;
  for (double i = std::floor(lo); i < hi; ++i) {
    cells.texel.push_back(static_cast<size_t>(Wrap(static_cast<long long>(i), n, wrap)));
    cells.overlap.push_back(Overlap(a, b, i));
  }
  return cells;
}

}  // namespace

double SrgbToLinear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double LinearToSrgb(double c) {
  return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

absl::StatusOr<TextureImage> DecodeTexture(const std::string& bytes, const std::string& name) {
  int width = 0, height = 0, channels = 0;
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(std::min<size_t>(bytes.size(), 1u << 30));
  if (stbi_info_from_memory(data, size, &width, &height, &channels) != 0 &&
      static_cast<uint64_t>(width) * static_cast<uint64_t>(height) > kMaxTextureTexels) {
    return absl::InvalidArgumentError(
        absl::StrCat(name, ": ", width, " x ", height, " texels, more than ", kMaxTextureTexels));
  }
  std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> pixels(
      stbi_load_from_memory(data, size, &width, &height, &channels, 4), stbi_image_free);
  if (!pixels || width <= 0 || height <= 0) {
    const char* reason = stbi_failure_reason();
    return absl::InvalidArgumentError(absl::StrCat(name, ": not an image stb_image reads (",
                                                   reason ? reason : "no reason given", ")"));
  }
  std::array<float, 256> linear{};
  for (int v = 0; v < 256; ++v) linear[v] = static_cast<float>(SrgbToLinear(v / 255.0));
  TextureImage image{width, height, {}, channels == 2 || channels == 4};
  image.texels.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
  for (size_t i = 0; i < image.texels.size(); ++i) {
    const stbi_uc* p = pixels.get() + 4 * i;
    image.texels[i] = {linear[p[0]], linear[p[1]], linear[p[2]], p[3] / 255.0f};
  }
  return image;
}

std::array<double, 4> TextureMean(const TextureImage& image, const std::vector<TexCoord>& uv,
                                  bool v_up, TextureWrapping wrap) {
  Polygon texels;  // in texel units, y down from the top row
  for (const TexCoord& c : uv) {
    texels.push_back({c[0] * image.width, (v_up ? 1 - c[1] : c[1]) * image.height});
  }
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[2] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  for (const TexCoord& p : texels) {
    for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  }
  const auto texel = [&](double x, double y) {
    const auto& t = image.texels[static_cast<size_t>(Wrap(static_cast<long long>(std::floor(y)),
                                                          image.height, wrap.v)) *
                                     static_cast<size_t>(image.width) +
                                 static_cast<size_t>(Wrap(static_cast<long long>(std::floor(x)),
                                                          image.width, wrap.u))];
    return std::array<double, 4>{t[0], t[1], t[2], t[3]};
  };
  const double area = Area(texels);
  if (texels.empty() || !std::isfinite(area)) return WholeImageMean(image);
  if (area <= 0) return texel(texels[0][0], texels[0][1]);
  if ((std::floor(hi[0]) - std::floor(lo[0]) + 1) * (std::floor(hi[1]) - std::floor(lo[1]) + 1) >
      kMaxFootprintTexels) {
    return WholeImageMean(image);
  }
  std::array<double, 4> sum{};
  if (const std::optional<std::array<double, 4>> r = AlignedRectangle(texels)) {
    // Separable: a texel's weight is its column's overlap times its row's.
    const AxisCells rows = CellsAlong(lo[1], hi[1], (*r)[2], (*r)[3], image.height, wrap.v);
    const AxisCells columns = CellsAlong(lo[0], hi[0], (*r)[0], (*r)[1], image.width, wrap.u);
    for (size_t j = 0; j < rows.texel.size(); ++j) {
      const std::array<float, 4>* line =
          image.texels.data() + rows.texel[j] * static_cast<size_t>(image.width);
      const double wy = rows.overlap[j];
      for (size_t i = 0; i < columns.texel.size(); ++i) {
        const double w = wy * columns.overlap[i];
        const std::array<float, 4>& t = line[columns.texel[i]];
        for (int c = 0; c < 4; ++c) sum[c] += w * static_cast<double>(t[c]);
      }
    }
    for (double& v : sum) v /= area;
    return sum;
  }
  // Row by row; in a row only the texels under its part of the polygon, and of those the
  // ones wholly inside a convex footprint (inside its part of the row at the row's top and
  // bottom lines) weigh 1 without clipping: the holodeck's slanted footprints spent 40% of
  // their load in clipping, most of it of texels wholly inside or wholly outside.
  const bool convex = Convex(texels);
  for (double y = std::floor(lo[1]); y < hi[1]; ++y) {
    const Polygon row = Clip(Clip(texels, 1, y, true), 1, y + 1, false);
    if (row.size() < 3) continue;
    double row_lo = row[0][0], row_hi = row[0][0];
    for (const TexCoord& p : row) row_lo = std::min(row_lo, p[0]), row_hi = std::max(row_hi, p[0]);
    double inside_lo = 0, inside_hi = -1;
    if (convex) {
      const auto bottom = SpanAt(row, y), top = SpanAt(row, y + 1);
      if (bottom && top) {
        inside_lo = std::max(bottom->first, top->first);
        inside_hi = std::min(bottom->second, top->second);
      }
    }
    for (double x = std::floor(row_lo); x < row_hi; ++x) {
      const double a = x >= inside_lo && x + 1 <= inside_hi
                           ? 1.0
                           : Area(Clip(Clip(row, 0, x, true), 0, x + 1, false));
      if (a <= 0) continue;
      const std::array<double, 4> t = texel(x, y);
      for (int c = 0; c < 4; ++c) sum[c] += a * t[c];
    }
  }
  for (double& s : sum) s /= area;
  return sum;
}

}  // namespace radflux
