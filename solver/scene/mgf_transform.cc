#include "solver/scene/mgf_transform.h"

#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "solver/scene/mgf_tokenizer.h"

namespace radflux {

Vec3 Mat3::operator*(const Vec3& v) const {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
          m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Mat3 Mat3::operator*(const Mat3& o) const {
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
    }
  }
  return r;
}

double Mat3::Determinant() const {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Mat3 Mat3::Inverse() const {
  const double inv_det = 1.0 / Determinant();
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      // Cofactor of element (j, i), from the cyclic minors.
      const int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
      r.m[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) * inv_det;
    }
  }
  return r;
}

Affine Affine::Then(const Affine& next) const {
  return {next.linear * linear, next.linear * offset + next.offset};
}

Affine Affine::Power(long long count) const {
  Affine result, base = *this;
  for (; count > 0; count >>= 1) {
    if (count & 1) result = result.Then(base);
    base = base.Then(base);
  }
  return result;
}

namespace {

// The numbers args[i+1 .. i+n]; error naming the option when they are missing or malformed.
absl::Status ReadNumbers(const std::vector<std::string>& args, size_t i, int n, double* out) {
  for (int k = 0; k < n; ++k) {
    if (i + 1 + k >= args.size() || !ParseMgfNumber(args[i + 1 + k], &out[k])) {
      return absl::InvalidArgumentError(
          absl::StrCat("xf option ", args[i], " needs ", n, " number", n > 1 ? "s" : ""));
    }
  }
  return absl::OkStatus();
}

// Rotation by `degrees` about coordinate axis `axis` (0 = x), right-handed.
Mat3 Rotation(int axis, double degrees) {
  const double r = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(r), s = std::sin(r);
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  Mat3 m;
  m.m[a][a] = c;
  m.m[a][b] = -s;
  m.m[b][a] = s;
  m.m[b][b] = c;
  return m;
}

// One elementary operation (-t, -r?, -s?, -m?) at args[i]; advances i past its numbers.
absl::StatusOr<Affine> ParseOperation(const std::vector<std::string>& args, size_t& i) {
  const std::string& op = args[i];
  const int axis = op.size() == 3 ? op[2] - 'x' : -1;
  const bool axis_ok = axis >= 0 && axis < 3;
  Affine t;
  double v[3];
  if (op == "-t") {
    if (absl::Status s = ReadNumbers(args, i, 3, v); !s.ok()) return s;
    t.offset = {v[0], v[1], v[2]};
    i += 3;
  } else if (op.size() == 3 && op[1] == 'r' && axis_ok) {
    if (absl::Status s = ReadNumbers(args, i, 1, v); !s.ok()) return s;
    t.linear = Rotation(axis, v[0]);
    i += 1;
  } else if (op == "-s" || (op.size() == 3 && op[1] == 's' && axis_ok)) {
    if (absl::Status s = ReadNumbers(args, i, 1, v); !s.ok()) return s;
    if (v[0] == 0) return absl::InvalidArgumentError(absl::StrCat("xf ", op, " 0: zero scale"));
    for (int k = 0; k < 3; ++k) {
      if (op == "-s" || k == axis) t.linear.m[k][k] = v[0];
    }
    i += 1;
  } else if (op.size() == 3 && op[1] == 'm' && axis_ok) {
    t.linear.m[axis][axis] = -1;
  } else {
    return absl::InvalidArgumentError(absl::StrCat("unknown xf option '", op, "'"));
  }
  return t;
}

}  // namespace

absl::StatusOr<XfProgram> ParseXfProgram(const std::vector<std::string>& args) {
  XfProgram program;
  program.segments.emplace_back();
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "-i" || args[i] == "-a") {
      const bool array = args[i] == "-a";
      long long n = 0;
      if (i + 1 >= args.size() || !ParseMgfInteger(args[i + 1], &n) || n < (array ? 1 : 0)) {
        return absl::InvalidArgumentError(
            absl::StrCat("xf ", args[i], " needs a count >= ", array ? "1" : "0"));
      }
      XfProgram::Segment next;
      next.repeat = n;
      if (array) {
        next.array = static_cast<int>(program.array_counts.size());
        program.array_counts.push_back(n);
      }
      program.segments.push_back(next);
      ++i;
      continue;
    }
    absl::StatusOr<Affine> op = ParseOperation(args, i);
    if (!op.ok()) return op.status();
    program.segments.back().ops = program.segments.back().ops.Then(*op);
  }
  return program;
}

Affine XfProgram::Evaluate(const std::vector<long long>& indices) const {
  Affine total;
  for (const Segment& s : segments) {
    total =
        total.Then(s.ops.Power(s.array >= 0 ? indices[static_cast<size_t>(s.array)] : s.repeat));
  }
  return total;
}

}  // namespace radflux
