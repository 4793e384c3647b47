// Camera: a pinhole camera in scene coordinates. Pixel (0, 0) is the image's top-left;
// x grows to the right, y downwards. The image's right is forward x up, so with +y up
// and looking along +z the scene's +x appears on the LEFT (as in the Cornell box photo).
#pragma once

#include "absl/status/status.h"
#include "solver/core/vec3.h"
#include "solver/raytrace/ray_caster.h"

namespace radflux {

struct Camera {
  Vec3 position;                       // eye point, scene units
  Vec3 look_at{0, 0, 1};               // a point the view centre passes through
  Vec3 up{0, 1, 0};                    // need not be orthogonal to the view direction
  double vertical_fov_degrees = 45.0;  // full vertical field of view
  int width = 512, height = 512;       // image size, pixels
};

// The Cornell box's published camera: eye (278, 273, -800) looking at (278, 273, 0),
// +y up, vertical field of view 39.3077 degrees.
Camera CornellCamera(int width, int height);

// OK when the size is positive, the fov in (0, 180), and eye, look-at and up are finite
// and not degenerate (look-at != eye, up not parallel to the view direction).
absl::Status ValidateCamera(const Camera& camera);

// Primary rays of a validated camera, with its frame precomputed.
class PinholeProjection {
 public:
  explicit PinholeProjection(const Camera& camera);
  // Ray from the eye through image point (x, y) in pixels (pixel centres at +0.5);
  // direction unit length, t_near 0.
  Ray RayThrough(double x, double y) const;

 private:
  Vec3 eye_, forward_, right_, up_;  // orthonormal; right_ and up_ scaled to the image plane
  double width_, height_;
};

}  // namespace radflux
