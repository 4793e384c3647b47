#include "solver/mesh/patch_mesh.h"

namespace radflux {
namespace {
double TriangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  return Length(Cross(b - a, c - a)) / 2;
}
}  // namespace

PatchPointSampler::PatchPointSampler(const PatchMesh& mesh, uint32_t p) {
  const Patch& patch = mesh.patches[p];
  a_ = mesh.positions[patch.v[0]];
  b_ = mesh.positions[patch.v[1]];
  c_ = mesh.positions[patch.v[2]];
  d_ = mesh.positions[patch.v[3]];
  first_ = patch.IsTriangle() ? 1.0 : TriangleArea(a_, b_, c_) / patch.area;
}

PatchMesh TranslatedMesh(const PatchMesh& mesh, const Vec3& offset) {
  PatchMesh moved = mesh;
  for (Vec3& p : moved.positions) p += offset;
  for (Patch& patch : moved.patches) patch.centroid += offset;
  return moved;
}

void FinishPatch(const std::vector<Vec3>& positions, const Vec3& face_normal, Patch& patch) {
  const Vec3& a = positions[patch.v[0]];
  const Vec3& b = positions[patch.v[1]];
  const Vec3& c = positions[patch.v[2]];
  const double abc = TriangleArea(a, b, c);
  Vec3 weighted = (a + b + c) * (abc / 3);
  double area = abc;
  if (!patch.IsTriangle()) {
    const Vec3& d = positions[patch.v[3]];
    const double acd = TriangleArea(a, c, d);
    weighted += (a + c + d) * (acd / 3);
    area += acd;
  }
  patch.area = area;
  patch.centroid = area > 0 ? weighted / area : (a + b + c) / 3;
  patch.normal = face_normal;
}

}  // namespace radflux
