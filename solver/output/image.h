// Image: a linear-light RGB float picture (radiance, W/m^2/sr per band), stored row-major
// with the top row first, and its two file forms: PFM (the linear floats as they are)
// and PNG (8 bits, tone mapped).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "solver/output/tone_map.h"

namespace radflux {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 * width * height floats, row y = 0 (top) first

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(3 * static_cast<size_t>(w) * h, 0.0f) {}
  float* Pixel(int x, int y) { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; }
  const float* Pixel(int x, int y) const { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; }
};

// Portable float map: "PF\n<width> <height>\n-1.0\n" (little endian), then float RGB
// rows from the BOTTOM row up, as the format requires.
absl::Status WritePfm(const std::string& path, const Image& image);

// 8-bit RGB PNG, each band tone mapped with `tone` (sRGB curve when tone.srgb).
absl::Status WritePng(const std::string& path, const Image& image, const ToneMapOptions& tone);

// The bytes WritePng writes (an in-memory PNG, e.g. for a glTF texture).
absl::StatusOr<std::string> EncodePng(const Image& image, const ToneMapOptions& tone);

}  // namespace radflux
