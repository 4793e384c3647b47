// field_error: error of a run's radiosity *field* against an independent reference, across
// different meshes (uniform, adaptive, hierarchical), so that a shadow edge drawn as a
// staircase counts against the run (compare_patch_values needs one mesh for both).
//
//   field_error reference SCENE.obj FINE.ply FINE.csv OUT.points [POINTS] [RAYS]
// spreads POINTS (default 50,000) points uniformly by area over FINE's mesh (stratified per
// patch, seeded) and computes at each point x a reference B(x) = E(x) + rho(x) (D(x) + I(x)):
// D, the direct light, from each emitting face of the scene: its exact unoccluded
// point-to-polygon form factor where 256 shadow rays to it are all clear, else the
// kernel-weighted mean over those 256 stratified points; I, one bounce of final gather: RAYS
// (default 1,024) cosine-distributed rays into FINE's solution (its B minus emission where they
// hit). So the reference has no mesh of its own: only I, smooth, depends on FINE. Points on
// emitters and hidden points (most gather rays hit a back face: the floor under a block, the
// ceiling above a lamp hung just below it) are left out.
//
//   field_error compare OUT.points RUN.ply RUN.csv [ERRORS.csv]
// looks each point up in the run's mesh (a short ray along the normal) and prints one line of
// JSON: rms / l1 = area-weighted RMS / mean of |B_run - B_ref| (B = r+g+b) over the mean of
// B_ref, with B constant per patch (what the solver computed); rms_smooth / l1_smooth: the
// same with B interpolated from the PLY's per-vertex values (what the picture shows);
// rms2_share: each object's share of rms^2. ERRORS.csv, if given, gets every point (x, y, z,
// object, reference B, run's B) for an error map.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "solver/core/sampling.h"
#include "solver/formfactor/polygon_form_factor.h"
#include "solver/output/patch_values_csv.h"
#include "solver/raytrace/embree_ray_caster.h"
#include "solver/scene/obj_loader.h"

namespace {

using radflux::Hit;
using radflux::PatchMesh;
using radflux::Rgb;
using radflux::Vec3;

// A lit mesh read back: PLY geometry + per-vertex B, CSV per-patch B and source face.
struct LitMesh {
  PatchMesh mesh;
  std::vector<Rgb> vertex_b;
  std::vector<Rgb> patch_b;
  std::vector<uint32_t> face;       // source face per patch
  std::vector<std::string> object;  // object name per patch
  std::unique_ptr<radflux::EmbreeRayCaster> caster;
};

bool Fail(const std::string& what) {
  std::fprintf(stderr, "field_error: %s\n", what.c_str());
  return false;
}

// Reads what solver/output/ply_writer.cc writes (binary: 9 floats + 3 bytes per vertex).
bool ReadPly(const std::string& path, LitMesh& lit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail("cannot open " + path);
  std::string line;
  size_t vertices = 0, faces = 0;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string a, b;
    size_t n = 0;
    if (words >> a >> b >> n && a == "element") (b == "vertex" ? vertices : faces) = n;
  }
  if (!in || vertices == 0) return Fail(path + ": not a radflux PLY");
  lit.mesh.positions.resize(vertices);
  lit.vertex_b.resize(vertices);
  for (size_t i = 0; i < vertices; ++i) {
    float f[9];
    unsigned char rgb[3];
    in.read(reinterpret_cast<char*>(f), sizeof f);
    in.read(reinterpret_cast<char*>(rgb), sizeof rgb);
    lit.mesh.positions[i] = {f[0], f[1], f[2]};
    lit.vertex_b[i] = {f[6], f[7], f[8]};
  }
  lit.mesh.patches.resize(faces);
  for (radflux::Patch& patch : lit.mesh.patches) {
    unsigned char count = 0;
    int32_t v[4] = {0, 0, 0, 0};
    in.read(reinterpret_cast<char*>(&count), 1);
    if (count != 3 && count != 4)
      return Fail(path + ": face with " + std::to_string(count) + " vertices");
    in.read(reinterpret_cast<char*>(v), 4 * count);
    if (count == 3) v[3] = v[2];
    for (int k = 0; k < 4; ++k) patch.v[k] = static_cast<uint32_t>(v[k]);
    const auto& p = lit.mesh.positions;
    const Vec3 n =
        radflux::Normalize(Cross(p[patch.v[1]] - p[patch.v[0]], p[patch.v[2]] - p[patch.v[0]]));
    radflux::FinishPatch(p, n, patch);
  }
  if (!in) return Fail(path + ": truncated");
  return true;
}

bool Load(const std::string& ply, const std::string& csv, LitMesh& lit) {
  if (!ReadPly(ply, lit)) return false;
  auto values = radflux::ReadPatchValuesCsv(csv);
  if (!values.ok()) return Fail(std::string(values.status().message()));
  if (values->size() != lit.mesh.size())
    return Fail(csv + " and " + ply + " differ in patch count");
  for (const radflux::PatchValue& v : *values) {
    lit.patch_b.push_back(v.radiosity);
    lit.face.push_back(v.face);
    lit.object.push_back(v.object);
  }
  auto caster = radflux::EmbreeRayCaster::Create(lit.mesh);
  if (!caster.ok()) return Fail(std::string(caster.status().message()));
  lit.caster = std::move(*caster);
  return true;
}

double Sum(const Rgb& b) { return b[0] + b[1] + b[2]; }

// B = r+g+b at x on `lit`, constant and interpolated; false when no front face lies under x.
bool Lookup(const LitMesh& lit, const Vec3& x, const Vec3& n, double delta, double& constant,
            double& smooth, uint32_t* patch_out = nullptr) {
  const Hit hit = lit.caster->Intersect({x + n * delta, -n, 0, 2 * delta});
  if (hit.patch == radflux::kNoPatch || Dot(hit.normal, n) <= 0) return false;
  const radflux::Patch& patch = lit.mesh.patches[hit.patch];
  if (patch_out) *patch_out = hit.patch;
  constant = Sum(lit.patch_b[hit.patch]);
  // Barycentric weights in the fan triangle (v0, vk, vk+1) that holds x.
  const auto& p = lit.mesh.positions;
  smooth = constant;
  for (int k = 1; k + 1 < patch.VertexCount(); ++k) {
    const Vec3 a = p[patch.v[0]], b = p[patch.v[k]], c = p[patch.v[k + 1]];
    const double area = Dot(Cross(b - a, c - a), n);
    const double wb = Dot(Cross(x - a, c - a), n) / area, wc = Dot(Cross(b - a, x - a), n) / area;
    if (wb < -1e-6 || wc < -1e-6 || wb + wc > 1 + 1e-6) continue;
    smooth = (1 - wb - wc) * Sum(lit.vertex_b[patch.v[0]]) + wb * Sum(lit.vertex_b[patch.v[k]]) +
             wc * Sum(lit.vertex_b[patch.v[k + 1]]);
    break;
  }
  return true;
}

// A convex polygon sampled uniformly by area (fan triangles chosen by the stratified u.x).
struct PolygonSampler {
  std::vector<Vec3> polygon;
  std::vector<double> cdf;  // fan triangle k covers [cdf[k], cdf[k+1])
  double area = 0;
  explicit PolygonSampler(std::vector<Vec3> p) : polygon(std::move(p)), cdf{0} {
    for (size_t k = 1; k + 1 < polygon.size(); ++k)
      cdf.push_back(cdf.back() +
                    0.5 * Length(Cross(polygon[k] - polygon[0], polygon[k + 1] - polygon[0])));
    area = cdf.back();
    for (double& c : cdf) c /= area;
  }
  Vec3 operator()(radflux::Point2 u) const {
    size_t k = 0;
    while (k + 2 < cdf.size() && u.x >= cdf[k + 1]) ++k;
    const double x = std::min((u.x - cdf[k]) / (cdf[k + 1] - cdf[k]), 0x1.fffffffffffffp-1);
    const auto [b0, b1] = radflux::SampleUniformTriangle({x, u.y});
    return polygon[0] * b0 + polygon[k + 1] * b1 + polygon[k + 2] * (1 - b0 - b1);
  }
};

struct Emitter {
  PolygonSampler sampler;
  Vec3 normal;  // unit, front side
  Rgb emission;
};

constexpr uint32_t kShadowPoints = 256;

// Form factor from the differential area (x, n) to the emitter, with visibility.
double DirectFormFactor(const LitMesh& fine, const Emitter& e, const Vec3& x, const Vec3& n,
                        double delta, uint32_t seed) {
  if (Dot(x - e.sampler.polygon[0], e.normal) <= 0) return 0;  // behind the emitter
  double kernel = 0;
  bool all_clear = true;
  for (uint32_t i = 0; i < kShadowPoints; ++i) {
    const Vec3 y = e.sampler(radflux::MultiJitteredSample(i, kShadowPoints, seed));
    const Vec3 d = y - x;
    const double r2 = Dot(d, d), cx = Dot(d, n), cy = -Dot(d, e.normal);
    if (cx <= 0 || cy <= 0) continue;
    const bool blocked = fine.caster->Occluded({x + n * delta, d, 0, 1 - 1e-4});
    all_clear = all_clear && !blocked;
    if (!blocked) kernel += cx * cy / (std::numbers::pi * r2 * r2);
  }
  if (all_clear) return radflux::PointToPolygonFormFactor(x, n, e.sampler.polygon);
  return kernel * e.sampler.area / kShadowPoints;
}

struct RefPoint {
  Vec3 x, n;
  double weight = 0, b = 0;  // area represented; reference B = r+g+b
};

int Reference(int argc, char** argv) {
  auto scene = radflux::LoadObjFile(argv[2]);
  if (!scene.ok()) return Fail(std::string(scene.status().message())), 1;
  LitMesh fine;
  if (!Load(argv[3], argv[4], fine)) return 1;
  const size_t points = argc > 6 ? std::stoul(argv[6]) : 50000;
  const uint32_t rays = argc > 7 ? static_cast<uint32_t>(std::stoul(argv[7])) : 1024;

  std::vector<Emitter> emitters;
  for (const radflux::Face& f : scene->faces) {
    const radflux::Material& m = scene->materials[f.material];
    if (!m.IsEmitter()) continue;
    std::vector<Vec3> polygon = radflux::FacePolygon(*scene, f);
    const Vec3 normal = radflux::Normalize(radflux::PolygonNewellNormal(polygon));
    emitters.push_back({PolygonSampler(std::move(polygon)), normal, m.emission});
  }
  Vec3 lo = fine.mesh.positions[0], hi = lo;
  double total_area = 0;
  for (const Vec3& p : fine.mesh.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  for (const radflux::Patch& p : fine.mesh.patches) total_area += p.area;
  const double delta = 1e-5 * Length(hi - lo);

  // Per patch a share of the points proportional to its area.
  std::vector<std::pair<uint32_t, uint32_t>> share;  // patch, points on it
  double carry = 0;
  for (uint32_t p = 0; p < fine.mesh.size(); ++p) {
    carry += points * fine.mesh.patches[p].area / total_area;
    const uint32_t here = static_cast<uint32_t>(carry);
    carry -= here;
    const radflux::Material& m = scene->materials[scene->faces[fine.face[p]].material];
    if (here > 0 && !m.IsEmitter()) share.push_back({p, here});
  }
  std::vector<std::vector<RefPoint>> out(share.size());
  size_t buried = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : buried)
  for (size_t s = 0; s < share.size(); ++s) {
    const auto [p, here] = share[s];
    const radflux::Patch& patch = fine.mesh.patches[p];
    const radflux::Material& m = scene->materials[scene->faces[fine.face[p]].material];
    const radflux::PatchPointSampler sample(fine.mesh, p);
    const radflux::Frame frame = radflux::Frame::FromNormal(patch.normal);
    for (uint32_t i = 0; i < here; ++i) {
      const Vec3 x = sample(radflux::MultiJitteredSample(i, here, radflux::PatternSeed(1, p)));
      const uint32_t seed = radflux::PatternSeed(2, p, i);
      Rgb gathered{};
      uint32_t back = 0;
      for (uint32_t k = 0; k < rays; ++k) {
        const Vec3 d = frame.ToWorld(
            radflux::SampleCosineHemisphere(radflux::MultiJitteredSample(k, rays, seed)));
        const Hit hit = fine.caster->Intersect({x + patch.normal * delta, d});
        if (hit.patch == radflux::kNoPatch) continue;
        if (Dot(hit.normal, d) >= 0) {
          ++back;
          continue;
        }
        const Rgb& e = scene->materials[scene->faces[fine.face[hit.patch]].material].emission;
        for (int b = 0; b < 3; ++b) gathered[b] += fine.patch_b[hit.patch][b] - e[b];
      }
      if (2 * back > rays) {  // mostly under something: hidden from view
        ++buried;
        continue;
      }
      Rgb light{};
      for (size_t k = 0; k < emitters.size(); ++k) {
        const double f = DirectFormFactor(fine, emitters[k], x, patch.normal, delta,
                                          radflux::PatternSeed(3, p, i * 64 + k));
        for (int b = 0; b < 3; ++b) light[b] += f * emitters[k].emission[b];
      }
      double b_sum = 0;
      for (int b = 0; b < 3; ++b) b_sum += m.reflectance[b] * (light[b] + gathered[b] / rays);
      out[s].push_back({x, patch.normal, patch.area / here, b_sum});
    }
  }
  std::FILE* file = std::fopen(argv[5], "w");
  if (!file) return Fail(std::string("cannot write ") + argv[5]), 1;
  std::fprintf(file, "# field_error reference: x y z nx ny nz weight B(r+g+b)\n");
  size_t written = 0;
  for (const auto& list : out)
    for (const RefPoint& r : list) {
      std::fprintf(file, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", r.x.x, r.x.y, r.x.z, r.n.x,
                   r.n.y, r.n.z, r.weight, r.b);
      ++written;
    }
  std::fclose(file);
  std::printf("{\"points\": %zu, \"buried\": %zu, \"gather_rays\": %u, \"delta\": %.3g}\n", written,
              buried, rays, delta);
  return 0;
}

int Compare(int argc, char** argv) {
  std::ifstream in(argv[2]);
  if (!in) return Fail(std::string("cannot open ") + argv[2]), 1;
  LitMesh run;
  if (!Load(argv[3], argv[4], run)) return 1;
  std::vector<RefPoint> points;
  std::string line;
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    RefPoint r;
    if (!(words >> r.x.x >> r.x.y >> r.x.z >> r.n.x >> r.n.y >> r.n.z >> r.weight >> r.b))
      return Fail(std::string(argv[2]) + ": bad line '" + line + "'"), 1;
    points.push_back(r);
  }
  for (const Vec3& p : run.mesh.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double delta = 1e-5 * Length(hi - lo);
  double weight = 0, sum_ref = 0, err2 = 0, err1 = 0, err2s = 0, err1s = 0;
  size_t missed = 0;
  std::map<std::string, std::array<double, 2>> by_object;
  std::FILE* errors = argc == 6 ? std::fopen(argv[5], "w") : nullptr;
  if (errors)
    std::fprintf(errors, "x,y,z,object,reference,run\n");  // weight, weighted squared error
  for (const RefPoint& r : points) {
    double constant = 0, smooth = 0;
    uint32_t patch = 0;
    if (!Lookup(run, r.x, r.n, delta, constant, smooth, &patch)) {
      ++missed;
      continue;
    }
    if (errors)
      std::fprintf(errors, "%g,%g,%g,%s,%g,%g\n", r.x.x, r.x.y, r.x.z, run.object[patch].c_str(),
                   r.b, constant);
    auto& o = by_object[run.object[patch]];
    o[0] += r.weight;
    o[1] += r.weight * (constant - r.b) * (constant - r.b);
    weight += r.weight;
    sum_ref += r.weight * r.b;
    err2 += r.weight * (constant - r.b) * (constant - r.b);
    err1 += r.weight * std::abs(constant - r.b);
    err2s += r.weight * (smooth - r.b) * (smooth - r.b);
    err1s += r.weight * std::abs(smooth - r.b);
  }
  if (errors) std::fclose(errors);
  const double mean = sum_ref / weight;
  std::printf(
      "{\"points\": %zu, \"missed\": %zu, \"rms\": %.5g, \"l1\": %.5g, \"rms_smooth\": %.5g, "
      "\"l1_smooth\": %.5g, \"run_patches\": %zu",
      points.size(), missed, std::sqrt(err2 / weight) / mean, err1 / weight / mean,
      std::sqrt(err2s / weight) / mean, err1s / weight / mean, run.mesh.size());
  // Each object's share of the squared error (they add up to rms^2).
  std::printf(", \"rms2_share\": {");
  const char* sep = "";
  for (const auto& [name, o] : by_object) {
    std::printf("%s\"%s\": %.3f", sep, name.c_str(), o[1] / err2);
    sep = ", ";
  }
  std::printf("}}\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "reference" && argc >= 6 && argc <= 8) return Reference(argc, argv);
  if (mode == "compare" && (argc == 5 || argc == 6)) return Compare(argc, argv);
  std::fprintf(
      stderr,
      "usage: field_error reference SCENE.obj FINE.ply FINE.csv OUT.points [POINTS] [RAYS]\n"
      "       field_error compare OUT.points RUN.ply RUN.csv [ERRORS.csv]\n");
  return 2;
}
