// The MGF loader on hand-written text: vertices, faces, objects, transforms (xf, arrays,
// nesting, mirrors), includes, skipped entities and the errors' file:line.
#include "solver/scene/mgf_loader.h"

#include <string>

#include "gtest/gtest.h"
#include "solver/scene/import_rules.h"
#include "solver/scene/mgf_transform.h"
#include "solver/scene/validation.h"

namespace radflux {
namespace {

// A unit square in z = 0 (counter-clockwise about +z) named s0..s3.
constexpr const char* kSquare =
    "v s0 =\n p 0 0 0\nv s1 =\n p 1 0 0\nv s2 =\n p 1 1 0\nv s3 =\n p 0 1 0\n";

absl::StatusOr<Scene> Load(const std::string& text, std::map<std::string, std::string> files = {},
                           const MgfLimits& limits = {}) {
  return LoadMgfText(text, "main.mgf", ImportOptions{}, MgfReaderFromMap(std::move(files)), limits);
}

Vec3 Corner(const Scene& s, size_t face, size_t k) {
  return s.positions[s.faces[face].vertices[k]];
}

void ExpectNear(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.z, b.z, 1e-12);
}

std::string Error(const absl::StatusOr<Scene>& s) {
  EXPECT_FALSE(s.ok());
  return std::string(s.status().message());
}

TEST(MgfLoader, FacesVerticesAndNestedObjects) {
  absl::StatusOr<Scene> s =
      Load(std::string(kSquare) + "o room\no floor\nf s0 s1 s2 s3\no\nf s0 s1 s2\no\nf s2 s3 s0\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 3u);
  EXPECT_EQ(s->positions.size(), 4u);  // shared while the transform stays the same
  EXPECT_EQ(s->objects[s->faces[0].object], "room.floor");
  EXPECT_EQ(s->objects[s->faces[1].object], "room");
  EXPECT_EQ(s->objects[s->faces[2].object], "");
  EXPECT_EQ(s->FaceLocation(0), "main.mgf:11");
  ExpectNear(Corner(*s, 0, 2), {1, 1, 0});
}

TEST(MgfTransform, OperationsApplyInTheOrderWritten) {
  auto apply = [](std::vector<std::string> args, Vec3 p) {
    absl::StatusOr<XfProgram> xf = ParseXfProgram(args);
    EXPECT_TRUE(xf.ok()) << xf.status();
    return xf->Evaluate(std::vector<long long>(xf->array_counts.size(), 0)).Apply(p);
  };
  ExpectNear(apply({"-t", "1", "2", "3", "-rz", "90"}, {1, 0, 0}), {-2, 2, 3});
  ExpectNear(apply({"-rz", "90", "-t", "1", "2", "3"}, {1, 0, 0}), {1, 3, 3});
  ExpectNear(apply({"-rx", "90"}, {0, 1, 0}), {0, 0, 1});
  ExpectNear(apply({"-ry", "90"}, {0, 0, 1}), {1, 0, 0});
  ExpectNear(apply({"-s", "2", "-t", "1", "0", "0"}, {1, 1, 1}), {3, 2, 2});
  ExpectNear(apply({"-sy", "3"}, {1, 1, 1}), {1, 3, 1});
  ExpectNear(apply({"-t", "1", "0", "0", "-i", "3", "-t", "0", "1", "0"}, {0, 0, 0}), {1, 3, 0});
  absl::StatusOr<XfProgram> array =
      ParseXfProgram({"-t", "-21", "0", "0", "-a", "15", "-t", "3", "0", "0"});
  ASSERT_TRUE(array.ok());
  EXPECT_EQ(array->array_counts, std::vector<long long>{15});
  ExpectNear(array->Evaluate({4}).Apply({0, 0, 0}), {-9, 0, 0});
  EXPECT_TRUE(ParseXfProgram({"-my"})->Evaluate({}).Mirrors());
  EXPECT_FALSE(ParseXfProgram({"-q"}).ok());
  EXPECT_FALSE(ParseXfProgram({"-t", "1", "2"}).ok());
  EXPECT_FALSE(ParseXfProgram({"-s", "0"}).ok());
  EXPECT_FALSE(ParseXfProgram({"-a", "0"}).ok());
  EXPECT_FALSE(ParseXfProgram({"-i", "-1"}).ok());
}

TEST(MgfLoader, TransformAppliesWhereTheVertexIsUsedInnerFirst) {
  absl::StatusOr<Scene> s = Load(std::string(kSquare) +
                                 "xf -t 10 0 0\nxf -rz 90\nf s0 s1 s2 s3\nxf\nf s0 s1 s2\nxf\n"
                                 "f s0 s1 s2\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ExpectNear(Corner(*s, 0, 1), {10, 1, 0});  // rotated, then translated
  ExpectNear(Corner(*s, 1, 1), {11, 0, 0});
  ExpectNear(Corner(*s, 2, 1), {1, 0, 0});
}

TEST(MgfLoader, ArraysRepeatTheirStatements) {
  absl::StatusOr<Scene> s =
      Load(std::string(kSquare) + "xf -a 2 -t 5 0 0 -a 3 -t 0 5 0\nf s0 s1 s2\nxf\nf s0 s1 s2\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 7u);
  // Last index fastest, as MGF's parser counts.
  const Vec3 expected[6] = {{0, 0, 0}, {0, 5, 0}, {0, 10, 0}, {5, 0, 0}, {5, 5, 0}, {5, 10, 0}};
  for (size_t f = 0; f < 6; ++f) ExpectNear(Corner(*s, f, 0), expected[f]);
  ExpectNear(Corner(*s, 6, 0), {0, 0, 0});
  // Each element is an object named as MGF's standard parser names it: "a" and its indices.
  const char* names[7] = {"a0.0", "a0.1", "a0.2", "a1.0", "a1.1", "a1.2", ""};
  for (size_t f = 0; f < 7; ++f) EXPECT_EQ(s->objects[s->faces[f].object], names[f]) << f;
}

TEST(MgfLoader, ArrayElementsAreObjectsBelowTheOnesOpenAndAboveTheOnesInside) {
  absl::StatusOr<Scene> s = Load(std::string(kSquare) +
                                 "o room\nxf -a 2 -t 5 0 0\no chair\nf s0 s1 s2\no\n"
                                 "f s0 s1 s2\nxf\nf s0 s1 s2\no\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 5u);
  const char* names[5] = {"room.a0.chair", "room.a0", "room.a1.chair", "room.a1", "room"};
  for (size_t f = 0; f < 5; ++f) EXPECT_EQ(s->objects[s->faces[f].object], names[f]) << f;
}

TEST(MgfLoader, MirrorReversesWindingSoFacesKeepFacingTheirSide) {
  absl::StatusOr<Scene> s = Load(std::string(kSquare) + "xf -mx\nf s0 s1 s2 s3\nxf\n");
  ASSERT_TRUE(s.ok());
  EXPECT_GT(PolygonNewellNormal(FacePolygon(*s, s->faces[0])).z, 0);
  ExpectNear(Corner(*s, 0, 0), {0, 1, 0});
}

TEST(MgfLoader, PrimitivesAreTransformedWithTheirVertices) {
  absl::StatusOr<Scene> s =
      Load("v a =\n p 0 0 0\nv b =\n p 0 0 1\nxf -s 2 -t 1 0 0\ncyl a 0.5 b\nxf\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 16u);  // ImportOptions::curve_segments
  double area = 0, zmax = 0;
  for (const Face& f : s->faces) {
    area += Length(PolygonNewellNormal(FacePolygon(*s, f))) / 2;
    for (uint32_t v : f.vertices) zmax = std::max(zmax, s->positions[v].z);
  }
  EXPECT_NEAR(area, 4 * 16 * 2 * 0.5 * std::sin(3.14159265358979323846 / 16), 1e-9);
  EXPECT_NEAR(zmax, 2, 1e-12);
}

TEST(MgfLoader, IncludesAreRelativeToTheIncludingFile) {
  std::map<std::string, std::string> files = {
      {"lib/a.mgf", "i b.mgf\nf s0 s1 s2\n"},
      {"lib/b.mgf", std::string(kSquare) + "f s0 s1 s2 s3\n"},
  };
  absl::StatusOr<Scene> s = Load("i lib/a.mgf -t 0 0 5\nf s0 s1 s3\n", files);
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 3u);
  EXPECT_EQ(s->files, (std::vector<std::string>{"main.mgf", "lib/a.mgf", "lib/b.mgf"}));
  EXPECT_EQ(s->FaceLocation(0), "lib/b.mgf:9");
  EXPECT_EQ(s->FaceLocation(1), "lib/a.mgf:2");
  EXPECT_EQ(s->FaceLocation(2), "main.mgf:2");
  EXPECT_NEAR(Corner(*s, 0, 0).z, 5, 1e-12);  // the include's transform
  EXPECT_NEAR(Corner(*s, 2, 0).z, 0, 1e-12);  // vertices outlive their file
}

TEST(MgfLoader, ObjectsLeftOpenEndWithTheirFile) {
  absl::StatusOr<Scene> s = Load(
      "o a\ni open.mgf\nf s0 s1 s2\ni close.mgf\no c\nf s0 s1 s2\n",
      {{"open.mgf", std::string(kSquare) + "o b\nf s0 s1 s2\n"}, {"close.mgf", "o\nf s0 s1 s2\n"}});
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 4u);
  EXPECT_EQ(s->objects[s->faces[0].object], "a.b");
  EXPECT_EQ(s->objects[s->faces[1].object], "a");
  EXPECT_EQ(s->objects[s->faces[2].object], "");  // an include may close its parent's object
  EXPECT_EQ(s->objects[s->faces[3].object], "c");
}

TEST(MgfLoader, IncludeWithArrayRepeatsTheFile) {
  absl::StatusOr<Scene> s =
      Load("i part.mgf -a 3 -t 2 0 0\n", {{"part.mgf", std::string(kSquare) + "f s0 s1 s2\n"}});
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 3u);
  ExpectNear(Corner(*s, 2, 0), {4, 0, 0});
  EXPECT_EQ(s->objects[s->faces[2].object], "a2");
}

TEST(MgfLoader, SkippedAndUnknownEntitiesAreCountedOncePerKind) {
  absl::StatusOr<Scene> s = Load("ies lamp.ies\nir 1.5 0\nir 1.5 0\nfoo 1\nbar\n");
  ASSERT_TRUE(s.ok());
  const auto& fixups = s->import_log.fixups();
  ASSERT_EQ(fixups.size(), 3u);
  EXPECT_EQ(fixups[0].kind, "mgf_skipped_ies");
  EXPECT_EQ(fixups[1].count, 2u);
  EXPECT_EQ(fixups[2].count, 2u);
  EXPECT_EQ(fixups[2].first, "main.mgf:4 ('foo')");
}

TEST(MgfLoader, FaceWithHoleBecomesOneFace) {
  absl::StatusOr<Scene> s = Load(
      "v a =\n p 0 0 0\nv b =\n p 4 0 0\nv c =\n p 4 4 0\nv d =\n p 0 4 0\n"
      "v e =\n p 1 1 0\nv f =\n p 1 2 0\nv g =\n p 2 2 0\nv h =\n p 2 1 0\n"
      "fh a b c d - e f g h\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->faces.size(), 1u);
  EXPECT_NEAR(PolygonNewellNormal(FacePolygon(*s, s->faces[0])).z / 2, 15, 1e-12);
}

TEST(MgfLoader, FaceWithHoleKeepsItsAreaThroughTheImportRules) {
  // The bridged contour touches itself along the bridge; ear clipping must cover the square
  // minus the hole exactly, and the result must validate.
  absl::StatusOr<Scene> s = Load(
      "m lamp =\n sides 1\n ed 100\n"
      "v a =\n p 0 0 0\nv b =\n p 4 0 0\nv c =\n p 4 4 0\nv d =\n p 0 4 0\n"
      "v e =\n p 1 1 0\nv f =\n p 1 2 0\nv g =\n p 2 2 0\nv h =\n p 2 1 0\n"
      "fh a b c d - e f g h\n");
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_TRUE(ApplyImportRules(ImportOptions{}, *s).ok());
  EXPECT_TRUE(ValidateScene(*s).ok()) << ValidateScene(*s);
  double area = 0;
  for (const Face& f : s->faces) {
    const Vec3 n = PolygonNewellNormal(FacePolygon(*s, f));
    EXPECT_GT(n.z, 0);
    area += Length(n) / 2;
  }
  EXPECT_NEAR(area, 15, 1e-12);
}

TEST(MgfLoader, ErrorsNameFileAndLine) {
  EXPECT_EQ(Error(Load("v a =\n p 0 0 0\nf a a q\n")), "main.mgf:3: vertex 'q' is not defined");
  EXPECT_EQ(Error(Load("v a =\n p 0 x 0\n")), "main.mgf:2: 'p' argument 2 is not a number");
  EXPECT_EQ(Error(Load("m x =\n rd 1.5\n")), "main.mgf:2: 'rd' must be in [0, 1] (roughness >= 0)");
  EXPECT_EQ(Error(Load("xf\n")), "main.mgf:1: 'xf' ends a transform but none is open in this file");
  EXPECT_EQ(Error(Load("\nxf -t 1 0 0\n")),
            "main.mgf:2: xf transform is never closed (no matching 'xf' line)");
  EXPECT_EQ(Error(Load("f a b\n")), "main.mgf:1: 'f' needs at least 3 vertices");
  EXPECT_EQ(Error(Load("o\n")), "main.mgf:1: 'o' ends an object but none is open");
  EXPECT_EQ(Error(Load("\n\ni nosuch.mgf\n")),
            "main.mgf:3: cannot include 'nosuch.mgf': no such file");
  EXPECT_EQ(Error(Load("i a.mgf\n", {{"a.mgf", "\nv x =\n p 0 0\n"}})),
            "a.mgf:3: 'p' needs 3 numbers");
  EXPECT_EQ(Error(Load("sph c 1\n")), "main.mgf:1: vertex 'c' is not defined");
  EXPECT_EQ(Error(Load("v c =\n p 0 0 0\nring c 0 1\n")), "main.mgf:3: ring vertex normal is zero");
}

TEST(MgfLoader, IncludeCyclesAreRefused) {
  const std::string message =
      Error(Load("i a.mgf\n", {{"a.mgf", "i b.mgf\n"}, {"b.mgf", "\ni a.mgf\n"}}));
  EXPECT_EQ(message, "b.mgf:2: include cycle: main.mgf -> a.mgf -> b.mgf -> a.mgf");
  EXPECT_NE(Error(Load("i main.mgf\n", {{"main.mgf", "i main.mgf\n"}})).find("include cycle"),
            std::string::npos);
}

TEST(MgfLoader, HugeArraysAreRefusedNotRun) {
  MgfLimits limits;
  limits.max_statements = 10000;
  limits.max_faces = 1000;
  EXPECT_EQ(Error(Load("xf -a 1000000000 -t 1 0 0\nxf -a 1000000000\nxf\nxf\n", {}, limits)),
            "main.mgf:3: more than 10000 statements to run (xf array too large?)");
  EXPECT_EQ(Error(Load(std::string(kSquare) + "xf -a 5000 -t 1 0 0\nf s0 s1 s2\nxf\n", {}, limits)),
            "main.mgf:10: more than 1000 faces (xf array too large?)");
  // An include repeated by an array counts each element even when the file is empty.
  EXPECT_EQ(Error(Load("\ni e.mgf -a 1000000000\n", {{"e.mgf", ""}}, limits)),
            "main.mgf:2: more than 10000 statements to run (xf array too large?)");
  std::string many = "v a =\n p 0 0 0\nfh";
  for (int i = 0; i < 600; ++i) many += " a";
  EXPECT_EQ(Error(Load(many + "\n")), "main.mgf:3: 'fh' with more than 512 vertices");
  // Found by the fuzzer (a 10 s timeout): objects opened in an array and never closed made
  // every element join an ever longer name.
  EXPECT_EQ(Error(Load("xf -a 100000 -t 1 0 0\no room\nxf\n")),
            "main.mgf:2: objects nested deeper than 64 (an 'o' without its closing 'o'?)");
  ImportOptions options;
  options.curve_segments = 100000;
  EXPECT_FALSE(LoadMgfText("", "x.mgf", options, MgfReaderFromMap({})).ok());
}

}  // namespace
}  // namespace radflux
