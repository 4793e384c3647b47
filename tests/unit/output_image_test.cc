#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "solver/output/image.h"
#include "tests/unit/output_test_meshes.h"

namespace radflux {
namespace {

using output_testing::TempPath;

// 3x2 image whose pixel (x, y) holds (x, y, 0.5 + x + 10 y).
Image TestImage() {
  Image image(3, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      float* p = image.Pixel(x, y);
      p[0] = static_cast<float>(x);
      p[1] = static_cast<float>(y);
      p[2] = 0.5f + static_cast<float>(x + 10 * y);
    }
  }
  return image;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(OutputImage, PfmHeaderAndBottomRowFirst) {
  const std::string path = TempPath("image.pfm");
  ASSERT_TRUE(WritePfm(path, TestImage()).ok());
  const std::string bytes = ReadAll(path);
  const std::string header = "PF\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  ASSERT_EQ(bytes.size(), header.size() + 3 * 2 * 3 * sizeof(float));
  std::vector<float> data(18);
  std::memcpy(data.data(), bytes.data() + header.size(), data.size() * sizeof(float));
  // File row 0 is the image's bottom row (y = 1).
  for (int file_row = 0; file_row < 2; ++file_row) {
    const int y = 1 - file_row;
    for (int x = 0; x < 3; ++x) {
      const float* p = &data[3 * (3 * file_row + x)];
      EXPECT_EQ(p[0], x);
      EXPECT_EQ(p[1], y);
      EXPECT_EQ(p[2], 0.5f + static_cast<float>(x + 10 * y));
    }
  }
}

TEST(OutputImage, PngIsDecodableWithToneMappedBytes) {
  const std::string path = TempPath("image.png");
  ToneMapOptions tone;
  tone.scale = 0.25;
  tone.exposure_stops = 1;  // total multiplier 0.5
  const Image image = TestImage();
  ASSERT_TRUE(WritePng(path, image, tone).ok());
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels = stbi_load(path.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr) << stbi_failure_reason();
  EXPECT_EQ(width, 3);
  EXPECT_EQ(height, 2);
  for (size_t i = 0; i < image.rgb.size(); ++i) {
    EXPECT_EQ(pixels[i], ToneMapByte(image.rgb[i], tone)) << i;
  }
  EXPECT_EQ(pixels[3 * 1 + 0], 188);  // pixel (1, 0) red: radiance 1 -> 0.5 linear -> sRGB 188
  EXPECT_EQ(pixels[3 * 2 + 0], 255);  // radiance 2 -> 1.0
  stbi_image_free(pixels);
}

TEST(OutputImage, WriteErrorsNameTheFile) {
  const std::string pfm = "/nonexistent_radflux_dir/image.pfm";
  const absl::Status s = WritePfm(pfm, TestImage());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find(pfm), std::string::npos) << s;
  const std::string png = "/nonexistent_radflux_dir/image.png";
  const absl::Status t = WritePng(png, TestImage(), {});
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.message().find(png), std::string::npos) << t;
  EXPECT_FALSE(WritePng(TempPath("empty.png"), Image{}, {}).ok());
}

}  // namespace
}  // namespace radflux
