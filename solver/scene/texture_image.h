// Textures as the import rules read them (issue 19): an image decoded by stb_image into
// linear RGB (the sRGB transfer curve undone) and alpha, and the mean of the image over a
// face's footprint in texture space. The reflectance of a textured face is its material's
// Kd times that mean; a face whose mean alpha is 0 is fully cut out.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace radflux {

// A texture coordinate: u to the right, v as the format defines it (see TextureMean).
using TexCoord = std::array<double, 2>;

struct TextureImage {
  int width = 0, height = 0;
  // Row-major, row 0 the top row of the image file: linear red, green, blue in [0, 1]
  // (decoded from sRGB) and alpha in [0, 1] (1 when the file has none).
  std::vector<std::array<float, 4>> texels;
  bool has_alpha = false;  // the file has an alpha channel (grey + alpha, or RGBA)
};

// Largest image decoded (4096 x 4096): a bigger one (or a small file that claims to be) is
// refused before its pixels are allocated (16 bytes each here).
inline constexpr uint64_t kMaxTextureTexels = uint64_t{1} << 24;

// The image in `bytes` (PNG, JPEG, TGA, BMP, ... as stb_image reads them), named `name` in
// messages. INVALID_ARGUMENT "NAME: not an image stb_image reads (REASON)" otherwise, and
// "NAME: W x H texels, more than kMaxTextureTexels" for an image too large.
absl::StatusOr<TextureImage> DecodeTexture(const std::string& bytes, const std::string& name);

// The linear value of the sRGB-encoded value `c` in [0, 1] (IEC 61966-2-1).
double SrgbToLinear(double c);
// Its inverse: the sRGB-encoded value of the linear value `c` in [0, 1]. A grey image used
// as an alpha map is data, not colour: its texels' encoded value is the opacity.
double LinearToSrgb(double c);

// The texels covered by a footprint larger than this many are not visited one by one: the
// mean of the whole image stands for them (a face over that many texels of a repeating
// texture sees all of it about evenly).
inline constexpr double kMaxFootprintTexels = double{1 << 22};

// How texture space goes on outside [0, 1] along one axis (glTF's sampler wrapS / wrapT;
// OBJ's `-clamp on`): the image repeats, its edge texels stretch on (CLAMP_TO_EDGE), or it
// repeats mirrored every other period (MIRRORED_REPEAT).
enum class TextureWrap { kRepeat, kClampToEdge, kMirroredRepeat };
struct TextureWrapping {
  TextureWrap u = TextureWrap::kRepeat, v = TextureWrap::kRepeat;
};

// The mean of `image` (linear RGB and alpha) over the polygon `uv`, each texel a constant
// square weighted by the area of the polygon over it (exact for a polygon, up to rounding).
// Outside [0, 1] the image continues as `wrap` says, per axis. With `v_up` (OBJ), v = 0 is
// the bottom row of the image; otherwise (glTF) v = 0 is the top row. A polygon of zero area
// in texture space takes the texel under its first vertex. A footprint over more than
// kMaxFootprintTexels texels takes the whole image's mean (exact in the limit for repeat
// and mirrored repeat; for clamp-to-edge an approximation of such a footprint).
std::array<double, 4> TextureMean(const TextureImage& image, const std::vector<TexCoord>& uv,
                                  bool v_up, TextureWrapping wrap = {});

}  // namespace radflux
