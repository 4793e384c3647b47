// PNG images written by the texture tests (OBJ and glTF alike), and the linear value the
// loader gives an sRGB byte.
#pragma once

#include <stb/stb_image_write.h>

#include <string>
#include <vector>

#include "solver/scene/texture_image.h"

namespace radflux::testing {

// A PNG of `width` x `height` pixels of `channels` bytes each (rows from the top).
inline std::string EncodePng(int width, int height, int channels,
                             const std::vector<unsigned char>& pixels) {
  std::string bytes;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size);
      },
      &bytes, width, height, channels, pixels.data(), channels * width);
  return bytes;
}

// A PNG of `width` x `height` RGBA pixels (rows from the top).
inline std::string Png(int width, int height, const std::vector<unsigned char>& rgba) {
  return EncodePng(width, height, 4, rgba);
}

// A PNG of `width` x `height` grey pixels (one channel, no alpha; rows from the top).
inline std::string GreyPng(int width, int height, const std::vector<unsigned char>& grey) {
  return EncodePng(width, height, 1, grey);
}

// The linear value of sRGB byte `v` as DecodeTexture stores it (a float).
inline double Linear(unsigned char v) { return static_cast<float>(SrgbToLinear(v / 255.0)); }

}  // namespace radflux::testing
