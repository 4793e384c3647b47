#include "solver/scene/gltf_nodes.h"

#include <cmath>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

absl::Status NodeError(const tinygltf::Node& node, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(
      node.name.empty() ? "unnamed node" : absl::StrCat("node '", node.name, "'"), ": ", what));
}

bool AllFinite(const std::vector<double>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

// The rotation matrix of quaternion q = (x, y, z, w), normalised first.
absl::StatusOr<Mat4> RotationMatrix(const tinygltf::Node& node) {
  const std::vector<double>& q = node.rotation;
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(norm > 0) || !std::isfinite(norm))
    return NodeError(node, "rotation quaternion has zero (or overflowing) length");
  const double x = q[0] / norm, y = q[1] / norm, z = q[2] / norm, w = q[3] / norm;
  // One matrix column per line.
  // clang-format off
  return Mat4{1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
              2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
              2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
              0,                       0,                       0,                       1};
  // clang-format on
}

// The nodes the scene starts from (see FlattenNodes).
absl::StatusOr<std::vector<int>> RootNodes(const tinygltf::Model& model) {
  if (model.scenes.empty()) {
    std::vector<bool> is_child(model.nodes.size(), false);
    for (const tinygltf::Node& node : model.nodes) {
      for (int child : node.children) {
        if (child >= 0 && static_cast<size_t>(child) < is_child.size()) is_child[child] = true;
      }
    }
    std::vector<int> roots;
    for (size_t n = 0; n < is_child.size(); ++n) {
      if (!is_child[n]) roots.push_back(static_cast<int>(n));
    }
    return roots;
  }
  const int scene = model.defaultScene < 0 ? 0 : model.defaultScene;
  if (static_cast<size_t>(scene) >= model.scenes.size()) {
    return absl::InvalidArgumentError(absl::StrCat("default scene ", scene, " does not exist"));
  }
  return model.scenes[scene].nodes;
}

}  // namespace

Mat4 Multiply(const Mat4& a, const Mat4& b) {
  Mat4 m{};
  for (int column = 0; column < 4; ++column) {
    for (int row = 0; row < 4; ++row) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a[4 * k + row] * b[4 * column + k];
      m[4 * column + row] = sum;
    }
  }
  return m;
}

Vec3 TransformPoint(const Mat4& m, const Vec3& p) {
  return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
          m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
          m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

double LinearDeterminant(const Mat4& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
         m[8] * (m[1] * m[6] - m[5] * m[2]);
}

absl::StatusOr<Mat4> LocalMatrix(const tinygltf::Node& node) {
  if (!AllFinite(node.matrix) || !AllFinite(node.translation) || !AllFinite(node.rotation) ||
      !AllFinite(node.scale)) {
    return NodeError(node, "transform has a NaN or infinite value");
  }
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) return NodeError(node, "matrix must have 16 numbers");
    Mat4 m;
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
    return m;
  }
  Mat4 m = kIdentity;
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) return NodeError(node, "scale must have 3 numbers");
    for (int k = 0; k < 3; ++k) m[5 * k] = node.scale[k];
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) return NodeError(node, "rotation must have 4 numbers");
    absl::StatusOr<Mat4> rotation = RotationMatrix(node);
    if (!rotation.ok()) return rotation.status();
    m = Multiply(*rotation, m);
  }
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) return NodeError(node, "translation must have 3 numbers");
    for (int k = 0; k < 3; ++k) m[12 + k] = node.translation[k];
  }
  return m;
}

absl::StatusOr<std::vector<MeshInstance>> FlattenNodes(const tinygltf::Model& model) {
  absl::StatusOr<std::vector<int>> roots = RootNodes(model);
  if (!roots.ok()) return roots.status();
  std::vector<bool> reached(model.nodes.size(), false);
  std::vector<std::pair<int, Mat4>> stack;  // node, its parent's world transform
  for (auto it = roots->rbegin(); it != roots->rend(); ++it) stack.emplace_back(*it, kIdentity);
  std::vector<MeshInstance> instances;
  while (!stack.empty()) {
    const auto [n, parent] = stack.back();
    stack.pop_back();
    if (n < 0 || static_cast<size_t>(n) >= model.nodes.size()) {
      return absl::InvalidArgumentError(absl::StrCat("node ", n, " does not exist"));
    }
    if (reached[n]) {
      return absl::InvalidArgumentError(
          absl::StrCat("node ", n, " is reached twice (a cycle or a child of two parents)"));
    }
    reached[n] = true;
    const tinygltf::Node& node = model.nodes[n];
    absl::StatusOr<Mat4> local = LocalMatrix(node);
    if (!local.ok()) return local.status();
    const Mat4 world = Multiply(parent, *local);
    if (node.mesh >= 0 || node.mesh < -1) {
      if (static_cast<size_t>(node.mesh) >= model.meshes.size()) {
        return NodeError(node, absl::StrCat("mesh ", node.mesh, " does not exist"));
      }
      instances.push_back({n, node.mesh, world});
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
      stack.emplace_back(*it, world);
    }
  }
  return instances;
}

}  // namespace radflux
