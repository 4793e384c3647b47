// Every kind of bad scene is refused before any work, with a message that names the
// file, the line or face, and what is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "solver/scene/obj_loader.h"
#include "solver/scene/validation.h"

namespace radflux {
namespace {

const char* kMtl =
    "newmtl white\nKd 0.5 0.5 0.5\n"
    "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n"
    "newmtl mirror\nKd 1.0 0.5 0.5\n"
    "newmtl dark\nKd 0.5 0.5 0.5\nKe -1 0 0\n";

const char* kLamp = "o lamp\nusemtl lamp\nv 0 0 1\nv 0 1 1\nv 1 1 1\nf 1 2 3\n";

// Loads and validates; returns the first error message ("" when the scene is fine).
std::string Problem(const std::string& obj, const std::string& mtl = kMtl) {
  absl::StatusOr<Scene> scene = LoadObjText(obj, mtl, "bad.obj");
  if (!scene.ok()) return std::string(scene.status().message());
  const absl::Status status = ValidateScene(*scene);
  return status.ok() ? "" : std::string(status.message());
}

void ExpectProblem(const std::string& obj, const std::vector<std::string>& words) {
  const std::string message = Problem(obj);
  ASSERT_FALSE(message.empty()) << obj;
  for (const std::string& w : words) EXPECT_NE(message.find(w), std::string::npos) << message;
}

TEST(SceneValidation, AGoodSceneIsAccepted) {
  EXPECT_EQ(Problem(std::string(kLamp) + "o floor\nusemtl white\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 4 5 6\n"), "");
}

TEST(SceneValidation, NanAndInfiniteCoordinates) {
  ExpectProblem(std::string(kLamp) + "o f\nusemtl white\nv nan 0 0\nv 1 0 0\nv 1 1 0\nf 4 5 6\n",
                {"bad.obj:9", "NaN or infinite"});
  ExpectProblem(std::string(kLamp) + "o f\nusemtl white\nv inf 0 0\nv 1 0 0\nv 1 1 0\nf 4 5 6\n",
                {"NaN or infinite"});
}

TEST(SceneValidation, ZeroAreaFace) {
  ExpectProblem(std::string(kLamp) + "o f\nusemtl white\nv 0 0 0\nv 1 0 0\nv 2 0 0\nf 4 5 6\n",
                {"bad.obj:12", "zero-area"});
}

TEST(SceneValidation, NonPlanarFaceNamesTheTolerance) {
  ExpectProblem(std::string(kLamp) +
                    "o wall\nusemtl white\nv 0 0 0\nv 1 0 0\nv 1 1 0.1\nv 0 1 0\nf 4 5 6 7\n",
                {"bad.obj:13", "object 'wall'", "non-planar", "tolerance"});
}

TEST(SceneValidation, NonConvexFace) {
  ExpectProblem(std::string(kLamp) +
                    "o f\nusemtl white\nv 0 0 0\nv 2 0 0\nv 1 0.2 0\nv 2 2 0\nv 0 2 0\nf 4 5 6 7 8\n",
                {"non-convex"});
}

TEST(SceneValidation, ReflectanceOutsideZeroOne) {
  ExpectProblem(std::string(kLamp) + "o f\nusemtl mirror\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 4 5 6\n",
                {"material 'mirror'", "reflectance", "[0,1)"});
}

TEST(SceneValidation, NegativeEmission) {
  ExpectProblem(std::string(kLamp) + "o f\nusemtl dark\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 4 5 6\n",
                {"material 'dark'", "emission"});
}

TEST(SceneValidation, UnknownMaterial) {
  ExpectProblem(std::string(kLamp) + "o f\nusemtl gold\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 4 5 6\n",
                {"bad.obj:12", "unknown material 'gold'"});
}

TEST(SceneValidation, FaceWithoutMaterial) {
  ExpectProblem("o f\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n" + std::string(kLamp),
                {"bad.obj:5", "no material"});
}

TEST(SceneValidation, EmptyScene) { ExpectProblem("# nothing\n", {"empty scene"}); }

TEST(SceneValidation, NoEmitter) {
  ExpectProblem("o f\nusemtl white\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n", {"no emitter"});
}

TEST(SceneValidation, VertexIndexOutOfRange) {
  const std::string message = Problem(std::string(kLamp) + "o f\nusemtl white\nf 1 2 9\n");
  EXPECT_FALSE(message.empty());
}

// Indices that wrap to a valid vertex through tinyobjloader's int (2^63 + 1 became the
// last vertex) are refused on their own line, the index as written.
TEST(SceneValidation, FaceIndexBeyond32BitsIsRefusedNotWrapped) {
  const std::string floor = "o f\nusemtl white\nv 0 0 0\nv 1 0 0\nv 1 1 0\n";
  for (const std::string index : {"9223372036854775809", "9223372036854775808",
                                  "-9223372036854775809", "-99999999999999999999", "2147483648"}) {
    EXPECT_EQ(Problem(std::string(kLamp) + floor + "f 4 5 " + index + "\n"),
              "bad.obj:12: face index " + index + " is out of range");
  }
  EXPECT_EQ(Problem(std::string(kLamp) + floor + "f 4/1 5/18446744073709551617 6/1\n"),
            "bad.obj:12: face index 18446744073709551617 is out of range");
  // The largest index that fits is still only out of this file's range.
  EXPECT_NE(Problem(std::string(kLamp) + floor + "f 4 5 2147483647\n").find("out of range"),
            std::string::npos);
}

// tinyobjloader reads a colour word it cannot parse as 0: NaN and infinite Kd/Ke values are
// refused naming the MTL (as the OBJ's mtllib names it) and its line.
TEST(SceneValidation, NonFiniteMtlColoursAreRefused) {
  const std::string lamp_nan = "newmtl white\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd nan 0.5 0.5\nKe 1 1 1\n";
  EXPECT_EQ(Problem(kLamp, lamp_nan), "scene.mtl:4: Kd value 'nan' is not a finite number");
  EXPECT_EQ(Problem(std::string("mtllib room.mtl\n") + kLamp, lamp_nan),
            "room.mtl:4: Kd value 'nan' is not a finite number");
  EXPECT_EQ(Problem(kLamp, "newmtl lamp\nKd 0.5 0.5 0.5\n  Ke inf 1 1\n"),
            "scene.mtl:3: Ke value 'inf' is not a finite number");
  EXPECT_EQ(Problem(kLamp, "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1e999\n"),
            "scene.mtl:3: Ke value '1e999' is not a finite number");
  // Colours the solve does not read stay as tinyobjloader reads them.
  EXPECT_EQ(Problem(kLamp, "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\nKs nan 0 0\n"), "");
}

// On disk the MTL is read beside the OBJ and named by its path.
TEST(SceneValidation, NonFiniteMtlColourOnDiskNamesTheMtlFile) {
  const std::string dir = ::testing::TempDir() + "/radflux_mtl_nan";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/lamp.obj") << "mtllib lamp.mtl\n" << kLamp;
  std::ofstream(dir + "/lamp.mtl") << "newmtl lamp\nKd 0.5 0.5 0.5\nKe inf 1 1\n";
  absl::StatusOr<Scene> scene = LoadObjFile(dir + "/lamp.obj");
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.status().message(), dir + "/lamp.mtl:3: Ke value 'inf' is not a finite number");
  std::filesystem::remove_all(dir);
}

TEST(SceneValidation, MissingFileIsNamed) {
  absl::StatusOr<Scene> scene = LoadObjFile("/nonexistent/scene.obj");
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.status().message().find("/nonexistent/scene.obj"), std::string::npos);
}

// Inputs the fuzzer once found troublesome, kept as data: none may crash or hang.
TEST(SceneValidation, FuzzCorpusNeverCrashes) {
  for (const char* text : {"f 1 2 3\n", "v 1 2\nf 1 1 1\n", "f -5 -6 -7\n", "usemtl\nf\n",
                           "v 1e400 0 0\nv 0 0 0\nv 0 1 0\nf 1 2 3\n", "o\ng\nf 0 0 0\n",
                           "mtllib \nv 0 0 0\nv 0 0 0\nv 0 0 0\nf 1/1/1 2//2 3\n"}) {
    (void)Problem(text);
  }
}

}  // namespace
}  // namespace radflux
