// RenderPark's MGF scenes (../shared/scenes/renderpark/) as the MGF loader reads them
// (before the import rules): the face counts (checked by hand for corridor, examp1 and floor_gloss
// from their f statements and primitives at 16 segments), emitters present, and what the conversion
// left out logged.
#include <string>
#include <tuple>

#include "gtest/gtest.h"
#include "solver/scene/load_scene.h"
#include "solver/scene/mgf_loader.h"
#include "solver/scene/validation.h"
#include "tests/source_path.h"

namespace radflux {
namespace {

const std::string kDir = testing::SourcePath("../shared/scenes/renderpark/");

struct Expected {
  const char* file;
  size_t faces, materials, objects, emitter_faces;
};

size_t EmitterFaces(const Scene& scene) {
  size_t n = 0;
  for (const Face& f : scene.faces) n += scene.materials[f.material].IsEmitter();
  return n;
}

bool Logged(const Scene& scene, const std::string& kind) {
  for (const ImportFixup& f : scene.import_log.fixups()) {
    if (f.kind == kind) return true;
  }
  return false;
}

TEST(MgfRenderPark, EverySceneLoadsWithItsLights) {
  // corridor: 67 f (57 of them the lights, from xf arrays) + 2 cyl x 16 + torus 16 x 16 +
  // sph 16 x 8. examp1: 2 x (cyl 16 + 12 f + 2 prisms of 15 sides + 2 caps + 7 f) + 15 x 4 f.
  // Objects include each xf array element's (MGF's "a<i>"): corridor's lights are 4 arrays
  // of up to 19 (lights.a0 .. lights.a18); examp1 has 2 lamps (a0.lamp, a1.lamp, ...) and
  // 15 vanes (a0.reflector.vane .. a14.reflector.vane).
  const Expected scenes[] = {
      {"cube.mgf", 66, 9, 10, 2},
      {"corridor.mgf", 67 + 32 + 256 + 128, 9, 12 + 19, 57},
      {"examp1.mgf", 2 * (16 + 12 + 2 * 17 + 7) + 60, 4, 47, 32},
      {"floor_gloss.mgf", 8 + 128, 4, 3, 1},
      {"office2/office2.mgf", 422, 24, 41, 1},
      {"salon/classroom.mgf", 5250, 26, 632, 24},
  };
  for (const Expected& e : scenes) {
    absl::StatusOr<Scene> scene = LoadMgfFile(kDir + e.file, ImportOptions{});
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->faces.size(), e.faces) << e.file;
    EXPECT_EQ(scene->materials.size(), e.materials) << e.file;
    EXPECT_EQ(scene->objects.size(), e.objects) << e.file;
    EXPECT_EQ(EmitterFaces(*scene), e.emitter_faces) << e.file;
    EXPECT_EQ(scene->files, std::vector<std::string>{kDir + e.file});
  }
}

TEST(MgfRenderPark, SpecularPartsAreLoggedOncePerKind) {
  absl::StatusOr<Scene> corridor = LoadMgfFile(kDir + "corridor.mgf", ImportOptions{});
  ASSERT_TRUE(corridor.ok());
  ASSERT_TRUE(Logged(*corridor, "mgf_specular_reflection_left_out"));
  for (const ImportFixup& f : corridor->import_log.fixups()) {
    if (f.kind == "mgf_specular_reflection_left_out") {
      EXPECT_EQ(f.count, 8u);  // all but the light
    }
  }
  // "groen" is cxy 0 0.38, outside every RGB gamut.
  EXPECT_TRUE(Logged(*corridor, "mgf_colour_out_of_gamut"));
  // Faces 7 on are the first array of lights, one face per element.
  EXPECT_EQ(corridor->objects[corridor->faces[6].object], "murenrechts");
  EXPECT_EQ(corridor->objects[corridor->faces[10].object], "lights.a3");
}

// The share of the light they scatter that the diffuse solve leaves out, from the files:
// examp1's aluminium (rs .75, rs .9; no rd) is all specular; floor_gloss's "rood" has rd 0.1
// and rs 0.5.
TEST(MgfRenderPark, SpecularSharesLeftOutAreCounted) {
  for (const auto& [file, count, share] :
       {std::tuple{"examp1.mgf", 2u, 1.0}, std::tuple{"floor_gloss.mgf", 1u, 0.5 / 0.6}}) {
    absl::StatusOr<Scene> scene = LoadMgfFile(kDir + file, ImportOptions{});
    ASSERT_TRUE(scene.ok()) << scene.status();
    const ImportFixup* specular = nullptr;
    for (const ImportFixup& f : scene->import_log.fixups()) {
      if (f.kind == "mgf_specular_reflection_left_out") specular = &f;
    }
    ASSERT_NE(specular, nullptr) << file;
    EXPECT_EQ(specular->count, count) << file;
    EXPECT_NEAR(specular->ShareMean(), share, 1e-12) << file;
    EXPECT_NEAR(specular->share_max, share, 1e-12) << file;
  }
}

TEST(MgfRenderPark, LoadSceneReadsMgfByItsExtension) {
  absl::StatusOr<Scene> scene = LoadScene(kDir + "cube.mgf", ImportOptions{});
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(scene->source, kDir + "cube.mgf");
  EXPECT_GT(EmitterFaces(*scene), 0u);
}

TEST(MgfRenderPark, EverySceneValidatesAfterTheImportRules) {
  // The loader hands over non-convex (corridor's floor) and non-planar (office2, classroom)
  // polygons as MGF gives them; LoadScene's import rules make every scene valid.
  for (const char* file : {"cube.mgf", "corridor.mgf", "examp1.mgf", "floor_gloss.mgf",
                           "office2/office2.mgf", "salon/classroom.mgf"}) {
    absl::StatusOr<Scene> scene = LoadScene(kDir + file, ImportOptions{});
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_TRUE(ValidateScene(*scene).ok()) << ValidateScene(*scene);
    EXPECT_GT(EmitterFaces(*scene), 0u) << file;
  }
}

TEST(MgfRenderPark, SidesGiveTwoSidedMaterials) {
  // examp1.mgf says `sides 1` in every material; corridor.mgf never says, so MGF's default
  // (two-sided) holds.
  absl::StatusOr<Scene> examp1 = LoadMgfFile(kDir + "examp1.mgf", ImportOptions{});
  absl::StatusOr<Scene> corridor = LoadMgfFile(kDir + "corridor.mgf", ImportOptions{});
  ASSERT_TRUE(examp1.ok() && corridor.ok());
  for (const Material& m : examp1->materials) EXPECT_FALSE(m.two_sided) << m.name;
  for (const Material& m : corridor->materials) EXPECT_TRUE(m.two_sided) << m.name;
}

TEST(MgfRenderPark, MaterialLibrariesLoadThroughIncludes) {
  // Materials/test.mgf includes the five libraries and uses OakWood from realobj.mgf.
  absl::StatusOr<Scene> scene = LoadMgfFile(kDir + "Materials/test.mgf", ImportOptions{});
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(scene->files.size(), 6u);
  EXPECT_EQ(scene->faces.size(), 2u);
  EXPECT_EQ(scene->materials[scene->faces[0].material].name, "OakWood");
  EXPECT_GT(scene->materials[scene->faces[0].material].reflectance[0], 0);
  EXPECT_EQ(EmitterFaces(*scene), 1u);
}

}  // namespace
}  // namespace radflux
