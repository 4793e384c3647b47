// ResultEncoder against EncodeResultChunks(MakeResultChunks(...)): the same bytes, and a blob
// file that reads back as them, for meshes of zero, one and several patch and vertex chunks.
#include "server/store/result_codec.h"

#include <gtest/gtest.h>

#include <random>

namespace radflux {
namespace {

// A mesh of `patches` quads over `patches` + 3 vertices (not a surface: only the encoding
// reads it), and B and its indirect part of every patch, from a fixed seed.
void MakeMesh(size_t patches, PatchMesh* mesh, SolveResult* solve, std::vector<Rgb>* indirect) {
  std::mt19937_64 random(patches);
  std::uniform_real_distribution<double> value(-1e3, 1e3);
  for (size_t i = 0; i < patches + 3; ++i)
    mesh->positions.push_back({value(random), value(random), value(random)});
  for (size_t i = 0; i < patches; ++i) {
    Patch patch;
    const auto v = static_cast<uint32_t>(i);
    patch.v = {v, v + 1, v + 2, i % 2 ? v + 2 : v + 3};
    patch.face = static_cast<uint32_t>(i / 7);
    mesh->patches.push_back(patch);
    solve->radiosity.push_back({value(random), value(random), value(random)});
    indirect->push_back({value(random), value(random), value(random)});
  }
}

TEST(ResultEncoderTest, FinishEqualsEncodingTheWholeResult) {
  for (size_t patches :
       {size_t{0}, size_t{1}, size_t{1000}, kResultChunkItems, 2 * kResultChunkItems + 5}) {
    PatchMesh mesh;
    SolveResult solve;
    std::vector<Rgb> indirect;
    MakeMesh(patches, &mesh, &solve, &indirect);
    const std::string report = R"({"solve": {"iterations": 7}})";
    const std::string whole = EncodeResultChunks(MakeResultChunks(mesh, solve, indirect, report));
    ResultEncoder encoder(mesh);
    absl::StatusOr<EncodedResult> encoded = std::move(encoder).Finish(solve, indirect, report);
    ASSERT_TRUE(encoded.ok()) << encoded.status();
    EXPECT_EQ(encoded->bytes, whole) << patches << " patches";
    // Its blob file (two zstd frames) reads back as those bytes.
    const std::string path = ::testing::TempDir() + "/result_codec_test.rfb";
    ASSERT_TRUE(WriteBuiltBlobFile(path, encoded->file).ok());
    absl::StatusOr<std::string> read = ReadBlobFile(path);
    ASSERT_TRUE(read.ok()) << read.status();
    EXPECT_EQ(*read, whole);
    // And it decodes to the chunks it encodes.
    absl::StatusOr<std::vector<v1::ResultChunk>> decoded = DecodeResultChunks(whole);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    EXPECT_EQ(decoded->back().report_json(), report);
    size_t indirect_values = 0;
    for (const v1::ResultChunk& chunk : *decoded) {
      if (!chunk.has_patches()) continue;
      for (int k = 0; k < chunk.patches().indirect_size(); ++k, ++indirect_values) {
        ASSERT_EQ(chunk.patches().indirect(k), indirect[indirect_values / 3][indirect_values % 3]);
      }
    }
    EXPECT_EQ(indirect_values, 3 * patches);
    // Header and report alone: the first and the last chunk, the same messages.
    absl::StatusOr<std::vector<v1::ResultChunk>> brief =
        DecodeResultChunks(whole, /*header_and_report_only=*/true);
    ASSERT_TRUE(brief.ok()) << brief.status();
    ASSERT_EQ(brief->size(), 2u);
    EXPECT_TRUE(brief->front().has_header());
    EXPECT_EQ(brief->front().header().patch_count(), patches);
    EXPECT_EQ(brief->back().report_json(), report);
  }
}

// B and I must each have a value per patch.
TEST(ResultEncoderTest, FinishRefusesValuesThatDoNotMatchThePatches) {
  PatchMesh mesh;
  SolveResult solve;
  std::vector<Rgb> indirect;
  MakeMesh(10, &mesh, &solve, &indirect);
  indirect.pop_back();
  EXPECT_FALSE(ResultEncoder(mesh).Finish(solve, indirect, "{}").ok());
}

}  // namespace
}  // namespace radflux
