#include "solver/output/image.h"

#include <stb/stb_image_write.h>

#include <bit>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "solver/output/output_file.h"

namespace radflux {
namespace {

static_assert(std::endian::native == std::endian::little, "PFM writer assumes little endian");

absl::Status CheckImage(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * static_cast<size_t>(image.width) * image.height) {
    return absl::InvalidArgumentError(absl::StrCat("image for '", path, "' is ", image.width, "x",
                                                   image.height, " with ", image.rgb.size(),
                                                   " values"));
  }
  return absl::OkStatus();
}

void AppendToString(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<size_t>(size));
}

}  // namespace

absl::Status WritePfm(const std::string& path, const Image& image) {
  if (absl::Status s = CheckImage(path, image); !s.ok()) return s;
  std::string out = absl::StrCat("PF\n", image.width, " ", image.height, "\n-1.0\n");
  const size_t row_bytes = 3 * sizeof(float) * static_cast<size_t>(image.width);
  const size_t header = out.size();
  out.resize(header + row_bytes * static_cast<size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    const size_t file_row = static_cast<size_t>(image.height - 1 - y);
    std::memcpy(out.data() + header + file_row * row_bytes, image.Pixel(0, y), row_bytes);
  }
  return WriteOutputFile(path, out, "PFM");
}

absl::StatusOr<std::string> EncodePng(const Image& image, const ToneMapOptions& tone) {
  std::vector<unsigned char> bytes(image.rgb.size());
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = ToneMapByte(image.rgb[i], tone);
  std::string out;
  if (!stbi_write_png_to_func(AppendToString, &out, image.width, image.height, 3, bytes.data(),
                              3 * image.width)) {
    return absl::InternalError("cannot encode PNG");
  }
  return out;
}

absl::Status WritePng(const std::string& path, const Image& image, const ToneMapOptions& tone) {
  if (absl::Status s = CheckImage(path, image); !s.ok()) return s;
  absl::StatusOr<std::string> out = EncodePng(image, tone);
  if (!out.ok()) return absl::InternalError(absl::StrCat("cannot encode PNG file '", path, "'"));
  return WriteOutputFile(path, *out, "PNG");
}

}  // namespace radflux
