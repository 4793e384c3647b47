// The import rules (issue 19): what each rule does to a small scene, that every kind of
// fix-up is one log line with its count and first file:line, and that --strict refuses
// instead, naming file:line as validation does.
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "solver/scene/face_shape.h"
#include "solver/scene/import_rules.h"
#include "solver/scene/obj_loader.h"
#include "solver/scene/validation.h"

namespace radflux {
namespace {

const char* kMtl =
    "newmtl white\nKd 0.5 0.5 0.5\n"
    "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n"
    "newmtl snow\nKd 1 1 0.5\n";

// A lamp triangle (lines 1-6 of every scene below), so that validation has an emitter.
const char* kLamp = "o lamp\nusemtl lamp\nv 0 0 5\nv 0 1 5\nv 1 1 5\nf 1 2 3\n";

Scene Load(const std::string& body, const ImportOptions& options = {}) {
  absl::StatusOr<Scene> scene = LoadObjText(std::string(kLamp) + body, kMtl, "s.obj");
  EXPECT_TRUE(scene.ok()) << scene.status();
  const absl::Status rules = ApplyImportRules(options, *scene);
  EXPECT_TRUE(rules.ok()) << rules;
  return *scene;
}

absl::Status StrictProblem(const std::string& body) {
  absl::StatusOr<Scene> scene = LoadObjText(std::string(kLamp) + body, kMtl, "s.obj");
  EXPECT_TRUE(scene.ok()) << scene.status();
  ImportOptions options;
  options.strict = true;
  return ApplyImportRules(options, *scene);
}

double TotalArea(const Scene& scene, size_t first_face) {
  double area = 0;
  for (size_t f = first_face; f < scene.faces.size(); ++f) {
    area += MeasureFace(FacePolygon(scene, scene.faces[f])).area;
  }
  return area;
}

const ImportFixup* Fixup(const Scene& scene, const std::string& kind) {
  for (const ImportFixup& f : scene.import_log.fixups()) {
    if (f.kind == kind) return &f;
  }
  return nullptr;
}

// An L-shaped hexagon of area 3 in z = 0 (its f on line 15), counter-clockwise from +z.
const char* kLShape =
    "o floor\nusemtl white\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
    "f 4 5 6 7 8 9\n";

TEST(ImportRules, NonConvexFaceIsTriangulatedInItsPlaneKeepingAreaAndFacing) {
  const Scene scene = Load(kLShape);
  ASSERT_EQ(scene.faces.size(), 1u + 4u);  // the lamp, and the hexagon's n - 2 triangles
  EXPECT_NEAR(TotalArea(scene, 1), 3.0, 1e-12);
  for (size_t f = 1; f < scene.faces.size(); ++f) {
    const FaceShape shape = MeasureFace(FacePolygon(scene, scene.faces[f]));
    EXPECT_NEAR(shape.normal.z, 1.0, 1e-12);  // still facing +z
    EXPECT_EQ(scene.faces[f].source_line, 15);
  }
  EXPECT_TRUE(ValidateScene(scene).ok()) << ValidateScene(scene);
  const ImportFixup* fix = Fixup(scene, "non_convex_triangulated");
  ASSERT_NE(fix, nullptr);
  EXPECT_EQ(fix->count, 1u);
  EXPECT_EQ(fix->first, "s.obj:15");
  EXPECT_EQ(scene.import_log.Lines(),
            std::vector<std::string>{"import: 1 non-convex face triangulated (first at s.obj:15)"});
}

TEST(ImportRules, StrictRefusesTheNonConvexFaceWithItsLine) {
  const absl::Status status = StrictProblem(kLShape);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("s.obj:15"), std::string::npos) << status;
  EXPECT_NE(status.message().find("non-convex"), std::string::npos) << status;
}

// A twisted quad: (0,0,0) (2,0,0) (2,1,0.5) (0,1,0); diagonal 0-2 is longer than 1-3.
const char* kTwisted =
    "o t\nusemtl white\nv 0 0 0\nv 2 0 0\nv 2 1 0.5\nv 0 1 0\nf 4 5 6 7\n";

TEST(ImportRules, NonPlanarQuadIsSplitAlongItsShorterDiagonal) {
  const Scene scene = Load(kTwisted);
  ASSERT_EQ(scene.faces.size(), 3u);
  // |v1 - v3| = sqrt(5) < |v0 - v2| = sqrt(5.25): both triangles hold the diagonal 1-3.
  for (size_t f = 1; f < 3; ++f) {
    const std::vector<uint32_t>& v = scene.faces[f].vertices;
    EXPECT_NE(std::find(v.begin(), v.end(), 4u), v.end());  // OBJ vertex 5 (0-based 4)
    EXPECT_NE(std::find(v.begin(), v.end(), 6u), v.end());  // OBJ vertex 7
  }
  EXPECT_TRUE(ValidateScene(scene).ok()) << ValidateScene(scene);
  ASSERT_NE(Fixup(scene, "non_planar_split"), nullptr);
  EXPECT_EQ(Fixup(scene, "non_planar_split")->count, 1u);
  EXPECT_NE(StrictProblem(kTwisted).message().find("non-planar"), std::string::npos);
}

TEST(ImportRules, ZeroAreaAndDuplicateFacesAreDroppedButABackToBackPairIsKept) {
  const std::string body =
      "o a\nusemtl white\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 4 5 6 7\n"  // line 13
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 9 10 11 8\n"                     // line 18: duplicate
      "f 7 6 5 4\n"                                                            // line 19: reverse
      "v 3 0 0\nv 4 0 0\nv 5 0 0\nf 12 13 14\n";                               // line 23: collinear
  const Scene scene = Load(body);
  ASSERT_EQ(scene.faces.size(), 3u);  // lamp, the quad and its reverse
  EXPECT_EQ(scene.faces[1].source_line, 13);
  EXPECT_EQ(scene.faces[2].source_line, 19);
  ASSERT_NE(Fixup(scene, "duplicate_dropped"), nullptr);
  EXPECT_EQ(Fixup(scene, "duplicate_dropped")->first, "s.obj:18");
  ASSERT_NE(Fixup(scene, "zero_area_dropped"), nullptr);
  EXPECT_EQ(Fixup(scene, "zero_area_dropped")->first, "s.obj:23");
  EXPECT_NE(StrictProblem(body).message().find("zero-area"), std::string::npos);
}

TEST(ImportRules, ManyFixesOfOneKindAreOneLineWithTheirCount) {
  std::string body = "o floor\nusemtl white\n";
  for (int k = 0; k < 50; ++k) {
    const int x = 3 * k, base = 4 + 6 * k;
    for (auto [px, py] : {std::pair{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}) {
      body += "v " + std::to_string(x + px) + " " + std::to_string(py) + " 0\n";
    }
    body += "f";
    for (int i = 0; i < 6; ++i) body += " " + std::to_string(base + i);
    body += "\n";
  }
  const Scene scene = Load(body);
  EXPECT_EQ(scene.faces.size(), 1u + 50u * 4u);
  ASSERT_EQ(scene.import_log.Lines().size(), 1u);
  EXPECT_EQ(Fixup(scene, "non_convex_triangulated")->count, 50u);
  EXPECT_EQ(Fixup(scene, "non_convex_triangulated")->first, "s.obj:15");
}

TEST(ImportRules, ALineSaysOneInTheSingularAndOtherCountsInThePlural) {
  ImportLog log;
  log.Add("clamped", "{material|materials} with reflectance >= 1 clamped to 0.98", "m 'a'");
  log.Add("overlap", "{pair|pairs} of faces {overlaps|overlap}", "a.obj:3", 0);
  log.Add("plain", "scene recentred", "", 2);
  EXPECT_EQ(log.Lines(),
            (std::vector<std::string>{
                "import: 1 material with reflectance >= 1 clamped to 0.98 (first at m 'a')",
                "import: 0 pairs of faces overlap (first at a.obj:3)",
                "import: 2 scene recentred"}));
  log.Add("clamped", "", "m 'b'", 2);
  EXPECT_EQ(log.fixups()[0].Text(), "materials with reflectance >= 1 clamped to 0.98");
  EXPECT_EQ((ImportFixup{"k", "a {b|c", 1, ""}.Text()), "a {b|c") << "unclosed: left as written";
}

TEST(ImportRules, ALineWithSharesSaysTheirMeanAndLargest) {
  ImportLog log;
  const std::string of = "of the light {it scatters|they scatter}";
  log.AddShare("left", "{material|materials} with a part left out", "a.mgf:3", 0.2, of);
  EXPECT_EQ(log.Lines()[0],
            "import: 1 material with a part left out: 20% of the light it scatters (first at "
            "a.mgf:3)");
  log.AddShare("left", "{material|materials} with a part left out", "a.mgf:9", 0.6, of);
  EXPECT_EQ(log.Lines()[0],
            "import: 2 materials with a part left out: 40% of the light they scatter on "
            "average, 60% at most (first at a.mgf:3)");
  EXPECT_NEAR(log.fixups()[0].ShareMean(), 0.4, 1e-15);
  EXPECT_EQ(log.fixups()[0].share_max, 0.6);
}

TEST(ImportRules, CoplanarOverlapsAreReportedAndEdgeNeighboursAreNot) {
  // Two unit squares side by side in z = 0 (sharing an edge), and a third square on the same
  // plane facing down (-z) over half of the first: one overlapping pair.
  const std::string body =
      "o a\nusemtl white\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 4 5 6 7\n"
      "v 2 0 0\nv 2 1 0\nf 5 8 9 6\n"
      "v 0.5 0 0\nv 0.5 1 0\nv 1.5 1 0\nv 1.5 0 0\nf 10 11 12 13\n";
  const Scene scene = Load(body);
  ASSERT_EQ(scene.faces.size(), 4u);  // reported, not changed
  const ImportFixup* fix = Fixup(scene, "coplanar_overlap");
  ASSERT_NE(fix, nullptr);
  EXPECT_EQ(fix->count, 2u);  // the third square overlaps both halves
  EXPECT_EQ(fix->first, "s.obj:13 and s.obj:21");
  const Scene apart = Load(
      "o a\nusemtl white\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 4 5 6 7\n"
      "v 2 0 0\nv 2 1 0\nf 5 8 9 6\nv 0 0 1e-3\nv 1 0 1e-3\nv 1 1 1e-3\nf 10 11 12\n");
  EXPECT_EQ(Fixup(apart, "coplanar_overlap"), nullptr);  // 1e-3 above: another plane
}

TEST(ImportRules, ReflectanceAtOrAboveOneIsClampedToTheMaximum) {
  const std::string body = "o s\nusemtl snow\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 4 5 6\n";
  const Scene scene = Load(body);
  const Material& snow = scene.materials[scene.faces[1].material];
  EXPECT_EQ(snow.reflectance, (Rgb{0.98, 0.98, 0.5}));
  EXPECT_EQ(Fixup(scene, "reflectance_clamped")->first, "material 'snow'");
  ImportOptions options;
  options.max_reflectance = 0.9;
  EXPECT_EQ(Load(body, options).materials[scene.faces[1].material].reflectance, (Rgb{0.9, 0.9, 0.5}));
  EXPECT_NE(StrictProblem(body).message().find("reflectance Kd 1 is outside [0,1)"), std::string::npos);
}

TEST(ImportRules, EmitMakesANamedMaterialAnEmitterAndAnUnknownNameIsAnError) {
  ImportOptions options;
  options.emit = {{"white", Rgb{1, 2, 3}}};
  const Scene scene = Load(kLShape, options);
  const Material& white = scene.materials[scene.faces[1].material];
  EXPECT_DOUBLE_EQ(white.emission[2], 3 * std::numbers::pi);  // E = pi * L_e
  absl::StatusOr<Scene> other = LoadObjText(std::string(kLamp) + kLShape, kMtl, "s.obj");
  options.emit = {{"chalk", Rgb{1, 1, 1}}};
  const absl::Status status = ApplyImportRules(options, *other);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("'chalk'"), std::string::npos) << status;
  EXPECT_NE(status.message().find("--emit"), std::string::npos) << status;
}

TEST(ImportRules, ASceneWithoutEmittersIsRefusedNamingTheOptionAndTheLargestMaterials) {
  std::string obj, mtl;
  for (int m = 0; m < 7; ++m) {  // material m covers a square of side m + 1
    const std::string name = "m" + std::to_string(m), s = std::to_string(m + 1);
    mtl += "newmtl " + name + "\nKd 0.5 0.5 0.5\n";
    obj += "usemtl " + name + "\nv 0 0 " + std::to_string(m) + "\nv " + s + " 0 " +
           std::to_string(m) + "\nv " + s + " " + s + " " + std::to_string(m) + "\nv 0 " + s + " " +
           std::to_string(m) + "\nf -4 -3 -2 -1\n";
  }
  absl::StatusOr<Scene> scene = LoadObjText(obj, mtl, "dark.obj");
  ASSERT_TRUE(scene.ok()) << scene.status();
  const absl::Status status = ValidateScene(*scene);
  EXPECT_EQ(std::string(status.message()),
            "dark.obj: no emitter (no face's material has Ke > 0); light it with --emit "
            "MATERIAL=R,G,B (emitted radiance L_e, repeatable); the materials with the largest "
            "area: 'm6' (49), 'm5' (36), 'm4' (25), 'm3' (16), 'm2' (9)");
}

}  // namespace
}  // namespace radflux
