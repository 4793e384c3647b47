// STL loading (solver/scene/stl_loader.h): ASCII and binary, the groups side file, and
// one file:line error for malformed input.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "solver/scene/stl_loader.h"
#include "solver/scene/validation.h"

namespace radflux {
namespace {

constexpr char kTwoFacets[] =
    "solid box\n"
    "  facet normal 0 0 1\n"
    "    outer loop\n"
    "      vertex 0 0 0\n"
    "      vertex 1 0 0\n"
    "      vertex 1 1 0\n"
    "    endloop\n"
    "  endfacet\n"
    "  facet normal 0 0 1\n"
    "    outer loop\n"
    "      vertex 0 0 0\n"
    "      vertex 1 1 0\n"
    "      vertex 0 1 2.5e-1\n"
    "    endloop\n"
    "  endfacet\n"
    "endsolid box\n";

std::string BinaryStl(int facets, const char* header = "solid but binary") {
  std::string bytes(84 + 50 * facets, '\0');
  std::memcpy(bytes.data(), header, std::strlen(header));
  const uint32_t count = facets;
  std::memcpy(bytes.data() + 80, &count, 4);
  for (int f = 0; f < facets; ++f) {
    const float v[12] = {0, 0, 1, 0, 0, float(f), 2, 0, float(f), 0, 3, float(f)};
    std::memcpy(bytes.data() + 84 + 50 * f, v, sizeof v);
  }
  return bytes;
}

TEST(StlLoader, AsciiFacetsBecomeTriangleSurfaces) {
  absl::StatusOr<Scene> scene = LoadStlBytes(kTwoFacets, "box.stl", std::nullopt);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->faces.size(), 2u);
  EXPECT_EQ(scene->faces[1].vertices.size(), 3u);
  EXPECT_EQ(scene->positions[scene->faces[1].vertices[2]].z, 0.25);
  EXPECT_EQ(scene->faces[1].source_line, 9);
  EXPECT_EQ(scene->objects[scene->faces[0].object], "facet1");
  EXPECT_EQ(scene->objects[scene->faces[1].object], "facet2");
  EXPECT_TRUE(ValidateScene(*scene, /*require_emitter=*/false).ok());
  EXPECT_FALSE(ValidateScene(*scene).ok());  // a light solve needs an emitter
}

TEST(StlLoader, BinaryIsRecognisedBySizeEvenWhenItStartsWithSolid) {
  absl::StatusOr<Scene> scene = LoadStlBytes(BinaryStl(3), "b.stl", std::nullopt);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->faces.size(), 3u);
  const Face& f = scene->faces[2];
  EXPECT_EQ(scene->positions[f.vertices[0]].z, 2);
  EXPECT_EQ(scene->positions[f.vertices[1]].x, 2);
  EXPECT_EQ(scene->positions[f.vertices[2]].y, 3);
}

TEST(StlLoader, GroupsSideFileNamesSurfaces) {
  absl::StatusOr<Scene> scene =
      LoadStlBytes(BinaryStl(3), "b.stl", "# one name per facet\nroof\n\n wall \nroof\n");
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->objects.size(), 2u);
  EXPECT_EQ(scene->objects[scene->faces[0].object], "roof");
  EXPECT_EQ(scene->objects[scene->faces[1].object], "wall");
  EXPECT_EQ(scene->faces[2].object, scene->faces[0].object);

  absl::StatusOr<Scene> short_file = LoadStlBytes(BinaryStl(3), "b.stl", "a\nb\n");
  ASSERT_FALSE(short_file.ok());
  EXPECT_EQ(short_file.status().message(), "b.stl.groups: 2 names for the 3 facets of b.stl");
  absl::StatusOr<Scene> long_file = LoadStlBytes(BinaryStl(1), "b.stl", "a\nb\n");
  ASSERT_FALSE(long_file.ok());
  EXPECT_EQ(long_file.status().message(), "b.stl.groups:2: more names than the 1 facets of b.stl");
}

TEST(StlLoader, MalformedAsciiNamesFileAndLine) {
  std::string text = kTwoFacets;
  text.replace(text.find("vertex 1 1 0"), 12, "vertex 1 x 0");
  absl::StatusOr<Scene> scene = LoadStlBytes(text, "m.stl", std::nullopt);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.status().message(), "m.stl:6: bad vertex coordinate 'x'");

  std::string four = kTwoFacets;
  four.replace(four.find("    endloop"), 11, "vertex 0 0 0\n endloop");
  scene = LoadStlBytes(four, "m.stl", std::nullopt);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.status().message(),
            "m.stl:7: a facet must have exactly 3 vertices (expected 'endloop')");

  scene = LoadStlBytes("hello", "m.stl", std::nullopt);
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.status().message().find("not an STL file"), std::string::npos);
}

// Every prefix of a valid file cut before its last 'endsolid' (a truncated download) is
// refused with one "file..." error line; never a crash.
TEST(StlLoader, EveryTruncationFailsCleanly) {
  const std::string text = kTwoFacets;
  for (size_t n = 0; n < text.rfind("endsolid") + 8; ++n) {
    absl::StatusOr<Scene> scene = LoadStlBytes(text.substr(0, n), "t.stl", std::nullopt);
    ASSERT_FALSE(scene.ok()) << n;
    EXPECT_EQ(scene.status().message().rfind("t.stl", 0), 0u) << scene.status();
    EXPECT_EQ(scene.status().message().find('\n'), std::string::npos);
  }
  const std::string binary = BinaryStl(2);
  for (size_t n = 0; n < binary.size(); n += 7) {
    EXPECT_FALSE(LoadStlBytes(binary.substr(0, n), "t.stl", std::nullopt).ok()) << n;
  }
}

}  // namespace
}  // namespace radflux
