// Subdivision: counts, conformity (no T-junctions inside a face), areas, provenance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "solver/mesh/contact_footprints.h"
#include "solver/mesh/subdivide.h"
#include "solver/scene/obj_loader.h"
#include "tests/source_path.h"
#include "tests/unit/test_scenes.h"

namespace radflux {
namespace {

Scene Cornell() {
  absl::StatusOr<Scene> scene = LoadObjFile(testing::SourcePath("scenes/cornell_box.obj"));
  EXPECT_TRUE(scene.ok()) << scene.status();
  return *scene;
}

double FaceArea(const Scene& scene, size_t f) {
  return Length(PolygonNewellNormal(FacePolygon(scene, scene.faces[f]))) / 2;
}

TEST(Subdivide, TargetPatchCountIsClose) {
  const Scene scene = Cornell();
  for (int64_t target : {100, 2000, 8500}) {
    absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, MeshOptions{target, 0});
    ASSERT_TRUE(mesh.ok());
    EXPECT_NEAR(double(mesh->size()), double(target), 0.1 * target) << target;
  }
}

TEST(Subdivide, SameCountGivesTheSameMesh) {
  const Scene scene = Cornell();
  const PatchMesh a = *SubdivideScene(scene, MeshOptions{1234, 0});
  const PatchMesh b = *SubdivideScene(scene, MeshOptions{1234, 0});
  ASSERT_EQ(a.size(), b.size());
  for (size_t p = 0; p < a.size(); ++p) EXPECT_EQ(a.patches[p].centroid, b.patches[p].centroid);
}

// A face's patches cover it but for the feet of the solids resting on it (the Cornell
// blocks' feet lie inside the floor) and what a face hung in front of it hides (the lamp).
TEST(Subdivide, PatchAreasSumToFaceAreasLessFootprintsAndKeepTheirFace) {
  const Scene scene = Cornell();
  const PatchMesh mesh = *SubdivideScene(scene, MeshOptions{3000, 0});
  const std::vector<FaceContacts> contacts = FindContacts(scene);
  std::vector<double> sum(scene.faces.size(), 0.0);
  for (const Patch& p : mesh.patches) {
    sum[p.face] += p.area;
    EXPECT_GT(p.area, 0);
  }
  size_t feet = 0;
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    double area = FaceArea(scene, f);
    for (const Footprint& foot : contacts[f].footprints) {
      area -= Length(PolygonNewellNormal(foot)) / 2;
    }
    feet += contacts[f].footprints.size();
    EXPECT_TRUE(contacts[f].lines.empty()) << f;  // walls meet the floor along its border
    EXPECT_NEAR(sum[f], area, 1e-9 * FaceArea(scene, f)) << f;
  }
  EXPECT_EQ(feet, 3u);  // the two blocks on the floor, the lamp hung below the ceiling
}

// Within a face every interior edge is shared by exactly two patches (in opposite
// directions) and boundary edges by one: no T-junctions. Faces in `except` are not checked
// (contact meshing splits patches near a contact and leaves T-junctions: contact_clip.h).
void ExpectConforming(const PatchMesh& mesh, const std::vector<size_t>& except = {}) {
  for (size_t f = 0; f + 1 < mesh.face_first_patch.size(); ++f) {
    if (std::find(except.begin(), except.end(), f) != except.end()) continue;
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (uint32_t p = mesh.face_first_patch[f]; p < mesh.face_first_patch[f + 1]; ++p) {
      const Patch& patch = mesh.patches[p];
      for (int k = 0; k < patch.VertexCount(); ++k) {
        ++directed[{patch.v[k], patch.v[(k + 1) % patch.VertexCount()]}];
      }
    }
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1) << "edge used twice in one direction, face " << f;
    }
    // Count vertices used by patches that lie strictly inside another patch's edge.
    for (uint32_t p = mesh.face_first_patch[f]; p < mesh.face_first_patch[f + 1]; ++p) {
      const Patch& patch = mesh.patches[p];
      for (int k = 0; k < patch.VertexCount(); ++k) {
        const Vec3 a = mesh.Vertex(p, k), b = mesh.Vertex(p, (k + 1) % patch.VertexCount());
        for (uint32_t v = mesh.face_first_vertex[f]; v < mesh.face_first_vertex[f + 1]; ++v) {
          const Vec3 q = mesh.positions[v];
          const double t = Dot(q - a, b - a) / Dot(b - a, b - a);
          if (t <= 1e-9 || t >= 1 - 1e-9) continue;
          EXPECT_GT(Length(a + (b - a) * t - q), 1e-9 * Length(b - a))
              << "T-junction in face " << f;
        }
      }
    }
  }
}

TEST(Subdivide, NoTJunctionsInQuadsTrianglesAndFans) {
  // 0: the floor, 1: the ceiling (contact meshing)
  ExpectConforming(*SubdivideScene(Cornell(), MeshOptions{400, 0}), {0, 1});
  const char* hexagon =
      "mtllib m.mtl\no hex\nusemtl w\nv 1 0 0\nv .5 .866 0\nv -.5 .866 0\nv -1 0 0\nv -.5 -.866 0\n"
      "v .5 -.866 0\nf 1 2 3 4 5 6\n";
  absl::StatusOr<Scene> scene = LoadObjText(hexagon, "newmtl w\nKd .5 .5 .5\nKe 1 1 1\n", "hex");
  ASSERT_TRUE(scene.ok()) << scene.status();
  const PatchMesh mesh = *SubdivideScene(*scene, MeshOptions{0, 0.3});
  EXPECT_EQ(mesh.size(), 6u * 4 * 4);  // 6 fan triangles, spokes of 1 -> n = 4
  ExpectConforming(mesh);
  double area = 0;
  for (const Patch& p : mesh.patches) area += p.area;
  EXPECT_NEAR(area, FaceArea(*scene, 0), 1e-12);
}

TEST(Subdivide, MaxEdgeBoundsEveryEdge) {
  const PatchMesh mesh = *SubdivideScene(Cornell(), MeshOptions{0, 50});
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    for (int k = 0; k < mesh.patches[p].VertexCount(); ++k) {
      EXPECT_LE(Length(mesh.Vertex(p, (k + 1) % mesh.patches[p].VertexCount()) - mesh.Vertex(p, k)),
                50 * 1.5);  // quads: each side <= 50 up to the skew of the face
    }
  }
  const MeshStats stats = ComputeMeshStats(mesh);
  EXPECT_EQ(stats.patches, mesh.size());
  EXPECT_GT(stats.min_area, 0);
  EXPECT_GE(stats.max_area, stats.min_area);
  EXPECT_GE(stats.max_aspect, 0.99);
}

// --max-edge 1e-300: the steps per side (~1e302) do not fit an int; they were cast to
// INT_MIN and meshed as one step each (148 patches, exit 0). Now the count is refused.
TEST(Subdivide, AMaxEdgeFarBelowTheSceneIsRefusedNotMeshedCoarsely) {
  for (const double edge : {1e-300, 1e-12}) {
    const absl::StatusOr<PatchMesh> mesh = SubdivideScene(Cornell(), MeshOptions{0, edge});
    ASSERT_FALSE(mesh.ok()) << edge << ": " << mesh->size() << " patches";
    EXPECT_EQ(mesh.status().code(), absl::StatusCode::kResourceExhausted);
    EXPECT_NE(mesh.status().message().find("would exceed 2^31 patches"), std::string::npos)
        << mesh.status().message();
  }
}

// A quad with cut lines is cut along each of them, and each interval between them is split
// as the edge length asks: a 1 x 1 quad cut at u = 0.1, v = 0.3 and 0.35, max edge 0.4, has
// grid lines at u = 0, 0.1, 0.4, 0.7, 1 and v = 0, 0.3, 0.35, 0.675, 1.
TEST(Subdivide, CutLinesAreGridLinesAndEachIntervalKeepsTheEdge) {
  int next = 1;
  const Scene scene = testing::SceneFromObj(
      testing::ObjQuad("plate", "white", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, next));
  QuadCutsByFace cuts;
  cuts[0] = QuadCuts{{0.1}, {0.3, 0.35}};
  absl::StatusOr<PatchMesh> mesh = SubdivideScene(scene, MeshOptions{0, 0.4}, cuts);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  std::set<double> xs, ys;
  for (uint32_t p = 0; p < mesh->size(); ++p) {
    for (int k = 0; k < 4; ++k) {
      xs.insert(std::round(mesh->Vertex(p, k).x * 1e9) / 1e9);
      ys.insert(std::round(mesh->Vertex(p, k).y * 1e9) / 1e9);
    }
  }
  EXPECT_EQ(xs, (std::set<double>{0, 0.1, 0.4, 0.7, 1}));
  EXPECT_EQ(ys, (std::set<double>{0, 0.3, 0.35, 0.675, 1}));
  EXPECT_EQ(mesh->size(), 4u * 4u);
  // Lines out of (0, 1) or out of order are refused, naming the face.
  for (const QuadCuts& bad : {QuadCuts{{0.5, 0.2}, {}}, QuadCuts{{}, {1.0}}}) {
    cuts[0] = bad;
    absl::StatusOr<PatchMesh> refused = SubdivideScene(scene, MeshOptions{0, 0.4}, cuts);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.status().message().find("cut lines must ascend"), std::string::npos)
        << refused.status().message();
  }
}

TEST(Subdivide, NormalsFaceIntoTheCornellBox) {
  const Scene scene = Cornell();
  const PatchMesh mesh = *SubdivideScene(scene, MeshOptions{200, 0});
  for (const Patch& p : mesh.patches) {
    const std::string& object = scene.objects[scene.faces[p.face].object];
    const Vec3 inward = object == "floor"                          ? Vec3{0, 1, 0}
                        : object == "ceiling" || object == "light" ? Vec3{0, -1, 0}
                        : object == "red_wall"                     ? Vec3{-1, 0, 0}
                        : object == "green_wall"                   ? Vec3{1, 0, 0}
                        : object == "back_wall"                    ? Vec3{0, 0, -1}
                                                                   : p.normal;
    EXPECT_GT(Dot(p.normal, inward), 0.99) << object;
  }
}

}  // namespace
}  // namespace radflux
