// The files a scene names (solver/scene/scene_references.h), found on disk as the loaders
// find them: what `radflux submit` sends with the scene.
#include "solver/scene/scene_references.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>

#include "solver/scene/file_lookup.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

class SceneReferencesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/radflux_refs_XXXXXX";
    dir_ = mkdtemp(pattern);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& path, const std::string& text) {
    const fs::path full = fs::path(dir_) / path;
    fs::create_directories(full.parent_path());
    std::ofstream(full, std::ios::binary) << text;
    return full.string();
  }
  std::string dir_;
};

TEST_F(SceneReferencesTest, ObjNamesItsMtlAndTheTexturesFoundIgnoringCase) {
  Write("m/a.mtl", "newmtl w\nKd 1 1 1\nmap_Kd -mm 0 1 TEX\\Wall.PNG\nmap_d missing.png\n");
  Write("tex/wall.png", "png");
  const std::string obj = Write("s.obj", "mtllib m/a.mtl\nv 0 0 0\n");
  absl::StatusOr<std::vector<std::string>> files = SceneReferences(obj);
  ASSERT_TRUE(files.ok()) << files.status();
  EXPECT_EQ(*files, (std::vector<std::string>{dir_ + "/m/a.mtl", dir_ + "/tex/wall.png"}))
      << "the texture is named relative to the OBJ's folder, as tinyobjloader reads it; "
         "the missing one is left out";
}

TEST_F(SceneReferencesTest, GltfNamesItsBuffersAndImagesButNotDataUris) {
  Write("bin/scene data.bin", "b");
  Write("img/a.png", "p");
  const std::string gltf =
      Write("s.gltf", R"({"buffers":[{"uri":"bin/scene%20data.bin"},{"uri":"data:,x"}],)"
                      R"("images":[{"uri":"img/a.png"}]})");
  absl::StatusOr<std::vector<std::string>> files = SceneReferences(gltf);
  ASSERT_TRUE(files.ok()) << files.status();
  EXPECT_EQ(*files, (std::vector<std::string>{dir_ + "/bin/scene data.bin", dir_ + "/img/a.png"}));
}

TEST_F(SceneReferencesTest, MgfIncludesAreFollowedAndAMissingOneIsTheLoadersError) {
  Write("lib/c.mgf", "\n");
  Write("parts/b.mgf", "i ../lib/c.mgf\n");
  const std::string main = Write("a.mgf", "i parts/b.mgf\n");
  absl::StatusOr<std::vector<std::string>> files = SceneReferences(main);
  ASSERT_TRUE(files.ok()) << files.status();
  EXPECT_EQ(*files, (std::vector<std::string>{dir_ + "/parts/b.mgf", dir_ + "/lib/c.mgf"}));
  const std::string broken = Write("d.mgf", "i nowhere.mgf\n");
  EXPECT_NE(SceneReferences(broken).status().message().find("d.mgf:1: cannot include"),
            std::string::npos);
  EXPECT_EQ(SceneReferences(dir_ + "/none.obj").status().code(), absl::StatusCode::kNotFound);
}

TEST_F(SceneReferencesTest, FindFileTriesTheExactNameFirstThenIgnoresCase) {
  Write("Dir/File.TXT", "x");
  EXPECT_EQ(FindFile(dir_, "Dir/File.TXT"), dir_ + "/Dir/File.TXT");
  EXPECT_EQ(FindFile(dir_, "dir\\file.txt"), dir_ + "/Dir/File.TXT");
  EXPECT_EQ(FindFile(dir_, "dir/other.txt"), std::nullopt);
  EXPECT_EQ(FindFile(dir_, "Dir"), std::nullopt) << "a folder is not a file";
}

}  // namespace
}  // namespace radflux
