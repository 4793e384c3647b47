// The public scenes of ../shared/scenes/ (issue 19) go in as downloaded: each loads through
// LoadScene with at most one line per kind of fix-up, validates, and the fix-up counts are
// the ones measured on these files. A missing ../shared fails the test (no silent skip).
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "solver/scene/load_scene.h"
#include "solver/scene/validation.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

const std::string kScenes = testing::SourcePath("../shared/scenes/");

// kind -> count of every fix-up logged, after checking there is one entry per kind and
// that the scene validates.
std::map<std::string, uint64_t> LoadAndCount(const std::string& file, const ImportOptions& options,
                                             size_t* faces = nullptr) {
  absl::StatusOr<Scene> scene = LoadScene(kScenes + file, options);
  EXPECT_TRUE(scene.ok()) << scene.status();
  if (!scene.ok()) return {};
  EXPECT_TRUE(ValidateScene(*scene).ok()) << ValidateScene(*scene);
  std::map<std::string, uint64_t> counts;
  for (const ImportFixup& f : scene->import_log.fixups()) {
    EXPECT_TRUE(counts.emplace(f.kind, f.count).second) << "two entries of kind " << f.kind;
  }
  EXPECT_EQ(scene->import_log.Lines().size(), counts.size());
  if (faces) *faces = scene->faces.size();
  return counts;
}

TEST(RealScenesImport, HolodeckWithItsOwnEmitters) {
  size_t faces = 0;
  const std::map<std::string, uint64_t> counts = LoadAndCount("holodeck/holodeck.obj", {}, &faces);
  // The walls' map_Kd (wall.png) and the screen's map_Ke (screen.png) are applied.
  EXPECT_EQ(counts, (std::map<std::string, uint64_t>{{"reflectance_from_textures", 161},
                                                     {"emission_from_textures", 3},
                                                     {"reflectance_clamped", 1},
                                                     {"repeated_vertices_removed", 4},
                                                     {"zero_area_dropped", 4},
                                                     {"non_planar_split", 44},
                                                     {"non_convex_triangulated", 79},
                                                     {"coplanar_overlap", 39}}));
  EXPECT_EQ(faces, 2228u);
}

TEST(RealScenesImport, HolodeckStrictIsRefusedAtTheFirstFaceToFix) {
  ImportOptions strict;
  strict.strict = true;
  absl::StatusOr<Scene> scene = LoadScene(kScenes + "holodeck/holodeck.obj", strict);
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.status().message().find("material 'door': reflectance Kd 1 is outside [0,1)"),
            std::string::npos)
      << scene.status();
}

TEST(RealScenesImport, ConferenceRoomLitByItsCeilingFixtures) {
  ImportOptions options;
  options.emit = {{"mesh16_SG", Rgb{20, 20, 20}}};
  size_t faces = 0;
  const std::map<std::string, uint64_t> counts =
      LoadAndCount("conference/conference.obj", options, &faces);
  EXPECT_EQ(counts, (std::map<std::string, uint64_t>{{"reflectance_clamped", 2},
                                                     {"coplanar_overlap", 5590}}));
  EXPECT_EQ(faces, 330837u);
}

TEST(RealScenesImport, ConferenceRoomWithoutLightsNamesTheOptionAndItsLargestMaterials) {
  absl::StatusOr<Scene> scene = LoadScene(kScenes + "conference/conference.obj", {});
  ASSERT_TRUE(scene.ok()) << scene.status();
  const absl::Status status = ValidateScene(*scene);
  EXPECT_NE(status.message().find("--emit MATERIAL=R,G,B"), std::string::npos) << status;
  EXPECT_NE(status.message().find("the materials with the largest area: '"), std::string::npos);
}

TEST(RealScenesImport, LostEmpireLitByItsTorches) {
  ImportOptions options;
  options.emit = {{"Torch", Rgb{20, 15, 8}}};
  size_t faces = 0;
  const std::map<std::string, uint64_t> counts =
      LoadAndCount("lost_empire/lost_empire.obj", options, &faces);
  // Every face takes Kd (1 for most materials) times its texel block's mean from map_Kd:
  // nothing is left at or above 1 to clamp. The water's map_d is partly transparent, at
  // least half opaque over every face: its 848 faces keep their opacity, none is dropped.
  EXPECT_EQ(counts, (std::map<std::string, uint64_t>{{"reflectance_from_textures", 112499},
                                                     {"partly_transparent", 848}}));
  EXPECT_EQ(faces, 112499u);
}

}  // namespace
}  // namespace radflux
