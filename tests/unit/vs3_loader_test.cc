// View3D .vs3 loading (solver/scene/vs3_loader.h): every record type View3D's GetVS3D reads,
// obstruction surfaces, and one file:line error for malformed input.
#include <gtest/gtest.h>

#include <string>

#include "solver/scene/validation.h"
#include "solver/scene/vs3_loader.h"

namespace radflux {
namespace {

// Two unit squares facing each other across a gap of 1, a triangle, and an obstruction.
constexpr char kModel[] =
    "T Two plates / with an obstruction\n"
    "! a comment line\n"
    "C encl=0, emit=0 eps=1.0e-5 maxU=6 maxO=2 minO=1 row=0 col=0 list=2 out=0 prjD=1\n"
    "F 3\n"
    "V 1  0 0 0\n"
    "V 2  1 0 0\n"
    "V 3  1 1 0\n"
    "V 4  0 1 0\n"
    "V 5  0 0 1\n"
    "V 6  1 0 1\n"
    "V 7  1 1 1\n"
    "V 8  0 1 1\n"
    "/ #  v1 v2 v3 v4 base cmbn emit name\n"
    "S 1  1  2  3  4  0    0    0.9  floor\n"
    "S 2  5  8  7  6  0    0    1.0  ceiling   ! emit 1.0 is clamped to 0.999\n"
    "s 3  1  2  6  0  0    0    0.5  floor\n"
    "O 4  1  3  7  5\n"
    "E\n"
    "anything after the end is ignored\n";

TEST(Vs3Loader, ReadsEveryRecordType) {
  absl::StatusOr<Vs3Model> model = LoadVs3Text(kModel, "m.vs3");
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_EQ(model->title, "Two plates");  // '/' starts a comment, as in View3D
  const Vs3Control& c = model->control;
  EXPECT_FALSE(c.enclosure);
  EXPECT_FALSE(c.emittances);
  EXPECT_DOUBLE_EQ(c.eps, 1e-5);
  EXPECT_EQ(c.max_u, 6);
  EXPECT_EQ(c.max_o, 4);  // View3D resets values below 4 to 4
  EXPECT_EQ(c.min_o, 1);
  EXPECT_EQ(c.list, 2);
  EXPECT_TRUE(c.prj_reverse);
  const Scene& s = model->scene;
  ASSERT_EQ(s.positions.size(), 8u);
  ASSERT_EQ(s.faces.size(), 4u);
  EXPECT_EQ(s.faces[0].vertices, (std::vector<uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(s.faces[2].vertices, (std::vector<uint32_t>{0, 1, 5}));  // v4 = 0: a triangle
  EXPECT_EQ(s.objects[s.faces[0].object], "floor");
  EXPECT_EQ(s.objects[s.faces[2].object], "floor#3");  // a repeated name stays its own surface
  EXPECT_FALSE(s.faces[2].obstruction);
  EXPECT_TRUE(s.faces[3].obstruction);
  EXPECT_EQ(s.faces[3].source_line, 17);
  EXPECT_DOUBLE_EQ(s.materials[s.faces[0].material].reflectance[0], 1 - 0.9);
  EXPECT_NEAR(s.materials[s.faces[1].material].reflectance[0], 0.001, 1e-12);
  EXPECT_TRUE(ValidateScene(s, /*require_emitter=*/false).ok());
}

TEST(Vs3Loader, EnclosureAndDefaults) {
  absl::StatusOr<Vs3Model> model =
      LoadVs3Text("C encl=1\nV 1 0 0 0\nV 2 1 0 0\nV 3 0 1 0\nS 1 1 2 3 0 0 0 0.9 a\n", "e.vs3");
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_TRUE(model->control.enclosure);
  EXPECT_EQ(model->control.max_u, 12);  // View3D 3.2's default
  EXPECT_DOUBLE_EQ(model->control.eps, 1e-4);
}

// Replaces line `line` (1-based) of kModel with `text` and returns the load error message.
std::string ErrorWithLine(int line, const std::string& text) {
  std::string model = kModel;
  size_t begin = 0;
  for (int k = 1; k < line; ++k) begin = model.find('\n', begin) + 1;
  model.replace(begin, model.find('\n', begin) - begin, text);
  absl::StatusOr<Vs3Model> loaded = LoadVs3Text(model, "m.vs3");
  return loaded.ok() ? "ok" : std::string(loaded.status().message());
}

TEST(Vs3Loader, MalformedRecordsNameFileAndLine) {
  EXPECT_EQ(ErrorWithLine(6, "V 3 1 0 0"), "m.vs3:6: vertex 3 out of sequence (expected 2)");
  EXPECT_EQ(ErrorWithLine(6, "V 2 1 zero 0"),
            "m.vs3:6: bad vertex coordinate 'zero' (a finite number)");
  EXPECT_EQ(ErrorWithLine(14, "S 1 1 2 3 9 0 0 0.9 floor"),
            "m.vs3:14: vertex 9 is not defined (8 vertices so far; V records come before the "
            "surfaces)");
  EXPECT_EQ(ErrorWithLine(14, "S 2 1 2 3 4 0 0 0.9 floor"),
            "m.vs3:14: surface 2 out of sequence (expected 1)");
  EXPECT_EQ(ErrorWithLine(14, "S 1 1 2 3 4 0 0 0.9"), "m.vs3:14: missing surface name");
  EXPECT_EQ(ErrorWithLine(14, "S 1 1 2 3 4 1 0 0.9 floor"),
            "m.vs3:14: subsurfaces (base > 0) and combined surfaces (cmbn > 0) are not supported");
  EXPECT_EQ(ErrorWithLine(14, "M 1 1 2 3 4 0 0 0.9 floor"),
            "m.vs3:14: mask (M) and null (N) surfaces are not supported by radflux");
  EXPECT_EQ(ErrorWithLine(16, "O 3 1 2 6 0"), "ok");  // obstructions may follow at once
  EXPECT_EQ(ErrorWithLine(4, "F 3a"), "m.vs3:4: only geometry format 'F 3' (vertex/surface) is supported");
  EXPECT_EQ(ErrorWithLine(3, "C encl=1 speed=2"),
            "m.vs3:3: unknown control word 'speed' (View3D's are eps, list, out, encl, emit, "
            "maxU, maxO, minO, row, col, prjD)");
  EXPECT_EQ(ErrorWithLine(3, "C encl"), "m.vs3:3: control word 'encl' has no value");
  EXPECT_EQ(ErrorWithLine(3, "C col=2"), "m.vs3:3: col needs row (as in View3D)");
  EXPECT_EQ(ErrorWithLine(2, "Q what"),
            "m.vs3:2: unknown record 'Q' (expected T, F, C, V, S, O, E, / or !)");
}

TEST(Vs3Loader, RadiatingSurfaceAfterObstructionIsRefused) {
  std::string model = kModel;
  model.replace(model.find("E\n"), 2, "S 5 1 2 3 4 0 0 0.9 late\nE\n");
  absl::StatusOr<Vs3Model> loaded = LoadVs3Text(model, "m.vs3");
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.status().message(),
            "m.vs3:18: radiating surface after an obstruction surface (all S come before O)");
}

// Every prefix of the model is read or refused with one "m.vs3..." line; never a crash.
TEST(Vs3Loader, EveryTruncationFailsCleanlyOrReads) {
  const std::string text = kModel;
  for (size_t n = 0; n < text.size(); ++n) {
    absl::StatusOr<Vs3Model> model = LoadVs3Text(text.substr(0, n), "m.vs3");
    if (model.ok()) continue;
    EXPECT_EQ(model.status().message().rfind("m.vs3", 0), 0u) << model.status();
    EXPECT_EQ(model.status().message().find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace radflux
