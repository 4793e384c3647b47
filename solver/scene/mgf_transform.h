// MGF transforms (the `xf` entity and the transform of `i`): 3x3 linear part plus offset,
// built from the argument list exactly as Greg Ward's MGF parser reads it (xf.c):
// operations apply to a point in the order written; `-i N` repeats the operations after it
// N times; `-a N` makes an array (element k repeats the operations after it k times).
// Supported operations: -t dx dy dz, -rx/-ry/-rz degrees (right-handed), -s f, -sx/-sy/-sz f,
// -mx/-my/-mz (mirror), -i N, -a N.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "solver/core/vec3.h"

namespace radflux {

// A 3x3 matrix acting on column vectors.
struct Mat3 {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Vec3 operator*(const Vec3& v) const;
  Mat3 operator*(const Mat3& o) const;
  double Determinant() const;
  // The inverse; only meaningful when Determinant() != 0.
  Mat3 Inverse() const;
};

// p -> linear * p + offset.
struct Affine {
  Mat3 linear;
  Vec3 offset;

  Vec3 Apply(const Vec3& p) const { return linear * p + offset; }
  // The transform that applies `this` first, then `next`.
  Affine Then(const Affine& next) const;
  // `this` applied `count` times (count >= 0), in O(log count) products.
  Affine Power(long long count) const;
  // True when the transform turns right-handed frames left-handed (faces must be reversed).
  bool Mirrors() const { return linear.Determinant() < 0; }
};

// An xf argument list parsed once: its operations grouped into segments, each applied a
// fixed number of times (-i) or as many times as an array's current element (-a).
struct XfProgram {
  struct Segment {
    Affine ops;            // the segment's operations composed, in the order written
    long long repeat = 1;  // times applied when not an array segment
    int array = -1;        // index into array_counts when the segment follows -a
  };
  std::vector<Segment> segments;
  std::vector<long long> array_counts;  // one per -a, in order (each >= 1)

  // The transform with `indices` choosing each array's element (one per array_counts entry,
  // each in [0, count)).
  Affine Evaluate(const std::vector<long long>& indices) const;
};

// Parses the words after "xf". Error (no location) for an unknown option, a missing or
// non-numeric argument, a zero scale, a negative -i count or an -a count below 1.
absl::StatusOr<XfProgram> ParseXfProgram(const std::vector<std::string>& args);

}  // namespace radflux
