#include "wire/proto_convert.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace radflux {

absl::StatusOr<JobOptions> FromProto(const v1::SolveOptions& p) {
  JobOptions o;
  if (p.has_target_patches()) o.mesh.target_patches = p.target_patches();
  if (p.has_max_edge()) o.mesh.max_edge = p.max_edge();
  if (p.has_form_factor_method()) {
    std::optional<FormFactorMethod> method = ParseMethod(p.form_factor_method());
    if (!method) {
      return absl::InvalidArgumentError(
          absl::StrCat("unknown form-factor method '", p.form_factor_method(), "'"));
    }
    o.form_factors.method = *method;
  }
  if (p.has_rays()) o.form_factors.rays = p.rays();
  if (p.has_hemicube_res()) o.form_factors.hemicube_res = p.hemicube_res();
  if (p.has_samples()) o.form_factors.samples = p.samples();
  if (p.has_cutoff()) o.form_factors.cutoff = p.cutoff();
  if (p.has_seed()) o.form_factors.seed = p.seed();
  if (p.has_block_size()) o.form_factors.block_size = p.block_size();
  if (p.has_solver()) {
    std::optional<SolverMethod> solver = ParseSolver(p.solver());
    if (!solver)
      return absl::InvalidArgumentError(absl::StrCat("unknown solver '", p.solver(), "'"));
    o.solver.method = *solver;
  }
  if (p.has_tolerance()) o.solver.tolerance = p.tolerance();
  if (p.has_max_iterations()) o.solver.max_iterations = p.max_iterations();
  return o;
}

v1::SolveOptions ToProto(const JobOptions& o) {
  v1::SolveOptions p;
  p.set_target_patches(o.mesh.target_patches);
  p.set_max_edge(o.mesh.max_edge);
  p.set_form_factor_method(std::string(MethodName(o.form_factors.method)));
  p.set_rays(o.form_factors.rays);
  p.set_hemicube_res(o.form_factors.hemicube_res);
  p.set_samples(o.form_factors.samples);
  p.set_cutoff(o.form_factors.cutoff);
  p.set_seed(o.form_factors.seed);
  p.set_block_size(o.form_factors.block_size);
  p.set_solver(std::string(SolverName(o.solver.method)));
  p.set_tolerance(o.solver.tolerance);
  p.set_max_iterations(o.solver.max_iterations);
  return p;
}

absl::StatusOr<ImportOptions> FromProto(const v1::ImportOptions& p) {
  ImportOptions o;
  if (p.has_max_reflectance()) o.max_reflectance = p.max_reflectance();
  o.strict = p.strict();
  o.two_sided = p.two_sided();
  if (p.has_curve_segments()) o.curve_segments = p.curve_segments();
  for (const v1::MaterialEmission& e : p.emit()) {
    const Rgb radiance{e.radiance().red(), e.radiance().green(), e.radiance().blue()};
    const bool valid = std::all_of(radiance.begin(), radiance.end(),
                                   [](double v) { return std::isfinite(v) && v >= 0; });
    if (e.material().empty() || !valid) {
      return absl::InvalidArgumentError(
          absl::StrCat("--emit '", e.material(), "=", radiance[0], ",", radiance[1], ",",
                       radiance[2], "': expected MATERIAL=R,G,B (emitted radiance L_e, three "
                       "numbers >= 0)"));
    }
    o.emit.emplace_back(e.material(), radiance);
  }
  return o;
}

v1::ImportOptions ToProto(const ImportOptions& o) {
  v1::ImportOptions p;
  p.set_max_reflectance(o.max_reflectance);
  p.set_strict(o.strict);
  p.set_two_sided(o.two_sided);
  p.set_curve_segments(o.curve_segments);
  for (const auto& [material, radiance] : o.emit) {
    v1::MaterialEmission* e = p.add_emit();
    e->set_material(material);
    e->mutable_radiance()->set_red(radiance[0]);
    e->mutable_radiance()->set_green(radiance[1]);
    e->mutable_radiance()->set_blue(radiance[2]);
  }
  return p;
}

bool IsTerminal(v1::JobState state) {
  return state == v1::JOB_STATE_SUCCEEDED || state == v1::JOB_STATE_FAILED ||
         state == v1::JOB_STATE_CANCELLED;
}

grpc::Status ToGrpcStatus(const absl::Status& status) {
  if (status.ok()) return grpc::Status::OK;
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()), std::string(status.message()));
}

absl::Status FromGrpcStatus(const grpc::Status& status) {
  if (status.ok()) return absl::OkStatus();
  return absl::Status(static_cast<absl::StatusCode>(status.error_code()), status.error_message());
}

uint16_t FloatToHalf(float value) {
  const uint32_t f = std::bit_cast<uint32_t>(value);
  const uint32_t sign = (f >> 16) & 0x8000u;
  const uint32_t abs = f & 0x7fffffffu;
  if (abs >= 0x7f800000u)
    return static_cast<uint16_t>(sign | 0x7c00u | (abs > 0x7f800000u ? 0x200u : 0u));
  if (abs >= 0x477ff000u) return static_cast<uint16_t>(sign | 0x7c00u);  // rounds past 65504
  if (abs < 0x38800000u) {  // subnormal half (or zero): value * 2^24 rounded to nearest even
    const float scaled = std::bit_cast<float>(abs) * 16777216.0f;
    const uint32_t m = static_cast<uint32_t>(scaled);
    const float frac = scaled - static_cast<float>(m);
    const uint32_t rounded = m + ((frac > 0.5f || (frac == 0.5f && (m & 1u))) ? 1u : 0u);
    return static_cast<uint16_t>(sign | rounded);
  }
  const uint32_t rebias = abs - 0x38000000u;  // exponent 127 -> 15
  const uint32_t half = rebias >> 13;
  const uint32_t rest = rebias & 0x1fffu;
  const uint32_t rounded = half + ((rest > 0x1000u || (rest == 0x1000u && (half & 1u))) ? 1u : 0u);
  return static_cast<uint16_t>(sign | rounded);
}

float HalfToFloat(uint16_t half) {
  const uint32_t sign = static_cast<uint32_t>(half & 0x8000u) << 16;
  const uint32_t exponent = (half >> 10) & 0x1fu;
  const uint32_t mantissa = half & 0x3ffu;
  if (exponent == 0) {
    const float v = static_cast<float>(mantissa) / 16777216.0f;
    return sign ? -v : v;
  }
  if (exponent == 31) return std::bit_cast<float>(sign | 0x7f800000u | (mantissa << 13));
  return std::bit_cast<float>(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

v1::Snapshot ToProtoSnapshot(int iteration, const std::vector<Rgb>& radiosity,
                             const std::vector<int>& bands, v1::SnapshotFormat format) {
  std::vector<int> chosen = bands.empty() ? std::vector<int>{0, 1, 2} : bands;
  const bool half = format == v1::SNAPSHOT_FORMAT_FLOAT16;
  v1::Snapshot s;
  s.set_iteration(iteration);
  s.set_patch_count(static_cast<uint32_t>(radiosity.size()));
  s.set_format(half ? v1::SNAPSHOT_FORMAT_FLOAT16 : v1::SNAPSHOT_FORMAT_FLOAT32);
  for (int b : chosen) s.add_bands(b);
  const size_t width = half ? 2 : 4;
  std::string data(radiosity.size() * chosen.size() * width, '\0');
  char* out = data.data();
  for (const Rgb& b : radiosity) {
    for (int band : chosen) {
      const float v = static_cast<float>(b[static_cast<size_t>(band)]);
      if (half) {
        const uint16_t h = FloatToHalf(v);
        std::memcpy(out, &h, sizeof(h));
      } else {
        std::memcpy(out, &v, sizeof(v));
      }
      out += width;
    }
  }
  s.set_data(std::move(data));
  return s;
}

absl::StatusOr<std::vector<float>> SnapshotValues(const v1::Snapshot& s) {
  const bool half = s.format() == v1::SNAPSHOT_FORMAT_FLOAT16;
  const size_t count = static_cast<size_t>(s.patch_count()) * static_cast<size_t>(s.bands_size());
  if (s.data().size() != count * (half ? 2 : 4)) {
    return absl::InvalidArgumentError("snapshot data size does not match its patches and bands");
  }
  std::vector<float> values(count);
  for (size_t i = 0; i < count; ++i) {
    if (half) {
      uint16_t h = 0;
      std::memcpy(&h, s.data().data() + 2 * i, 2);
      values[i] = HalfToFloat(h);
    } else {
      std::memcpy(&values[i], s.data().data() + 4 * i, 4);
    }
  }
  return values;
}

}  // namespace radflux
