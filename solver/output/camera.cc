#include "solver/output/camera.h"

#include <cmath>
#include <numbers>

namespace radflux {

Camera CornellCamera(int width, int height) {
  Camera camera;
  camera.position = {278, 273, -800};
  camera.look_at = {278, 273, 0};
  camera.up = {0, 1, 0};
  camera.vertical_fov_degrees = 39.3077;
  camera.width = width;
  camera.height = height;
  return camera;
}

absl::Status ValidateCamera(const Camera& camera) {
  if (camera.width <= 0 || camera.height <= 0) {
    return absl::InvalidArgumentError("camera image size must be positive");
  }
  if (!(camera.vertical_fov_degrees > 0 && camera.vertical_fov_degrees < 180)) {
    return absl::InvalidArgumentError("camera vertical field of view must be in (0, 180) degrees");
  }
  if (!IsFinite(camera.position) || !IsFinite(camera.look_at) || !IsFinite(camera.up)) {
    return absl::InvalidArgumentError("camera position, look-at and up must be finite");
  }
  const Vec3 view = camera.look_at - camera.position;
  if (!(Length(view) > 0)) return absl::InvalidArgumentError("camera look-at equals its position");
  if (!(Length(Cross(view, camera.up)) > 1e-12 * Length(view) * Length(camera.up))) {
    return absl::InvalidArgumentError("camera up is zero or parallel to the view direction");
  }
  return absl::OkStatus();
}

PinholeProjection::PinholeProjection(const Camera& camera)
    : eye_(camera.position), width_(camera.width), height_(camera.height) {
  forward_ = Normalize(camera.look_at - camera.position);
  const Vec3 right = Normalize(Cross(forward_, camera.up));
  const Vec3 up = Cross(right, forward_);
  const double half_height = std::tan(camera.vertical_fov_degrees * std::numbers::pi / 360.0);
  const double half_width = half_height * width_ / height_;
  right_ = right * half_width;
  up_ = up * half_height;
}

Ray PinholeProjection::RayThrough(double x, double y) const {
  const double sx = 2 * x / width_ - 1;   // -1 at the left edge, +1 at the right
  const double sy = 1 - 2 * y / height_;  // +1 at the top edge, -1 at the bottom
  Ray ray;
  ray.origin = eye_;
  ray.direction = Normalize(forward_ + right_ * sx + up_ * sy);
  return ray;
}

}  // namespace radflux
