// The node hierarchy of a glTF scene flattened into mesh instances: each node that holds a
// mesh, with its transform from the node's space to the scene's (local transforms, matrix or
// translation-rotation-scale, composed from the root down, as the glTF 2.0 spec says).
#pragma once

#include <array>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/vec3.h"
#include "tiny_gltf.h"

namespace radflux {

// A 4x4 affine transform, column-major as glTF stores it (element [4 * column + row]).
using Mat4 = std::array<double, 16>;

inline constexpr Mat4 kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// a * b (b applied first).
Mat4 Multiply(const Mat4& a, const Mat4& b);
// The point p transformed by m.
Vec3 TransformPoint(const Mat4& m, const Vec3& p);
// Determinant of m's upper-left 3x3: negative when m mirrors (and so flips winding).
double LinearDeterminant(const Mat4& m);

// A node's own transform: its `matrix`, or T * R * S from translation, rotation (unit
// quaternion x, y, z, w; normalised here) and scale. INVALID_ARGUMENT when an array has
// the wrong length, a value is not finite, or the quaternion's length is 0 or overflows.
absl::StatusOr<Mat4> LocalMatrix(const tinygltf::Node& node);

struct MeshInstance {
  int node = 0;            // index into model.nodes
  int mesh = 0;            // index into model.meshes
  Mat4 world = kIdentity;  // node space -> scene space
};

// Every node with a mesh under the roots of the model's default scene (scene 0 when none is
// set; all nodes that are no node's child when the model has no scene), in depth-first
// order, children in the order listed. INVALID_ARGUMENT (message without the file name)
// for a node index out of range, a node reached twice (a cycle or a shared child), a mesh
// index out of range or a bad local transform.
absl::StatusOr<std::vector<MeshInstance>> FlattenNodes(const tinygltf::Model& model);

}  // namespace radflux
