#include "solver/output/vertex_radiosity.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "solver/core/parallel.h"
#include "solver/output/gouraud_means.h"

namespace radflux {
namespace {

// Interior angle of patch p's corner at welded vertex w (radians).
double CornerAngle(const PatchMesh& mesh, const ShadingMesh& shading, uint32_t p, uint32_t w) {
  const Patch& patch = mesh.patches[p];
  const int n = patch.VertexCount();
  for (int k = 0; k < n; ++k) {
    if (shading.welded[patch.v[k]] != w) continue;
    const Vec3 here = mesh.positions[patch.v[k]];
    const Vec3 a = mesh.positions[patch.v[(k + n - 1) % n]] - here;
    const Vec3 b = mesh.positions[patch.v[(k + 1) % n]] - here;
    return std::atan2(Length(Cross(a, b)), Dot(a, b));
  }
  return 0;
}

// Patches whose edge holds welded vertex w as a T-junction, per vertex (CSR).
struct JunctionPatches {
  std::vector<uint32_t> first, patches;
  JunctionPatches(const ShadingMesh& s) : first(s.size() + 1, 0) {
    for (const TJunction& j : s.t_junctions) ++first[j.vertex + 1];
    for (size_t v = 0; v < s.size(); ++v) first[v + 1] += first[v];
    patches.resize(s.t_junctions.size());
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (const TJunction& j : s.t_junctions) patches[fill[j.vertex]++] = j.patch;
  }
};

// Adds the patches around every corner of the patches in `out` (through shared corners
// and T-junctions), keeping `out` sorted and unique.
void GrowRing(const PatchMesh& mesh, const ShadingMesh& s, const JunctionPatches& junctions,
              std::vector<uint32_t>& out) {
  // The ring's distinct corners first: a fan's hub is a corner of every patch around it, and
  // adding its patches once per such patch would cost n^2 for a fan of n patches.
  thread_local std::vector<uint32_t> corners;
  corners.clear();
  for (uint32_t p : out) {
    const Patch& patch = mesh.patches[p];
    for (int k = 0; k < patch.VertexCount(); ++k) corners.push_back(s.welded[patch.v[k]]);
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  for (uint32_t v : corners) {
    out.insert(out.end(), s.vertex_patches.begin() + s.first_patch[v],
               s.vertex_patches.begin() + s.first_patch[v + 1]);
    out.insert(out.end(), junctions.patches.begin() + junctions.first[v],
               junctions.patches.begin() + junctions.first[v + 1]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

// Whether the patches' centroids spread in two directions of the plane of `normal` (the
// smaller eigenvalue of their covariance is not negligible).
bool CentroidsSpanThePlane(const PatchMesh& mesh, const std::vector<uint32_t>& patches,
                           const Vec3& normal) {
  const Frame frame = Frame::FromNormal(normal);
  double mx = 0, my = 0, cxx = 0, cxy = 0, cyy = 0;
  for (uint32_t p : patches) {
    mx += Dot(mesh.patches[p].centroid, frame.s) / patches.size();
    my += Dot(mesh.patches[p].centroid, frame.t) / patches.size();
  }
  for (uint32_t p : patches) {
    const double x = Dot(mesh.patches[p].centroid, frame.s) - mx;
    const double y = Dot(mesh.patches[p].centroid, frame.t) - my;
    cxx += x * x, cxy += x * y, cyy += y * y;
  }
  const double root = std::hypot((cxx - cyy) / 2, cxy), half_trace = (cxx + cyy) / 2;
  return half_trace - root > 1e-6 * (half_trace + root);
}

// Drops the hidden patches (Patch::hidden) of `patches` when `shown_only`.
void KeepShown(const PatchMesh& mesh, bool shown_only, std::vector<uint32_t>& patches) {
  if (!shown_only) return;
  std::erase_if(patches, [&](uint32_t p) { return mesh.patches[p].hidden; });
}

// The patches a vertex's value is fitted to: those around it (using it as a corner or
// holding it on an edge); for a boundary vertex (the angles around it do not close to a
// full turn) also the patches around their corners, and a ring more (at most twice) while
// their centroids lie on a line. A vertex that a shown patch uses is fitted to shown patches
// only (a hidden patch's light stays in its slot), so it is a boundary vertex when hidden
// ones are around it.
void FitPatches(const PatchMesh& mesh, const ShadingMesh& s, const JunctionPatches& junctions,
                uint32_t w, std::vector<uint32_t>& out) {
  out.assign(s.vertex_patches.begin() + s.first_patch[w],
             s.vertex_patches.begin() + s.first_patch[w + 1]);
  out.insert(out.end(), junctions.patches.begin() + junctions.first[w],
             junctions.patches.begin() + junctions.first[w + 1]);
  const bool shown_only =
      std::any_of(out.begin(), out.end(), [&](uint32_t p) { return !mesh.patches[p].hidden; });
  double turn = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    if (shown_only && mesh.patches[out[i]].hidden) continue;
    const bool on_edge = i >= s.first_patch[w + 1] - s.first_patch[w];
    turn += on_edge ? std::numbers::pi : CornerAngle(mesh, s, out[i], w);
  }
  KeepShown(mesh, shown_only, out);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (std::abs(turn - 2 * std::numbers::pi) <= 1e-3) return;
  GrowRing(mesh, s, junctions, out);
  KeepShown(mesh, shown_only, out);
  for (int more = 0; more < 2 && !CentroidsSpanThePlane(mesh, out, s.normals[w]); ++more) {
    GrowRing(mesh, s, junctions, out);
    KeepShown(mesh, shown_only, out);
  }
}

using FitWeights = VertexFit::Weights;

// The farthest a vertex's value is extrapolated along a direction: its offset from the fit
// patches' mean centroid, in standard deviations of their centroids along it (a grid's
// boundary and corner vertices are at 2).
constexpr double kMaxExtrapolation = 4;

// Weights that give, for any patch values, the value at `at` of the area-weighted
// least-squares plane through the patches' (centroid, value) in the tangent plane of
// `normal`. Directions in which the centroids do not spread (a row of patches), or spread
// too little for the vertex's offset (kMaxExtrapolation), get zero slope: the weights'
// absolute sum is at most 1 + 2 kMaxExtrapolation.
FitWeights PlaneFitWeights(const PatchMesh& mesh, std::vector<uint32_t> patches, const Vec3& at,
                           const Vec3& normal) {
  const Frame frame = Frame::FromNormal(normal);
  double weight = 0, mx = 0, my = 0;
  for (uint32_t p : patches) {
    const Vec3 d = mesh.patches[p].centroid - at;
    const double a = mesh.patches[p].area;
    weight += a, mx += a * Dot(d, frame.s), my += a * Dot(d, frame.t);
  }
  FitWeights fit{std::move(patches), {}};
  fit.weights.assign(fit.patches.size(), 0);
  if (!(weight > 0)) return fit;
  mx /= weight, my /= weight;
  double cxx = 0, cxy = 0, cyy = 0;
  for (uint32_t p : fit.patches) {
    const Vec3 d = mesh.patches[p].centroid - at;
    const double a = mesh.patches[p].area;
    const double x = Dot(d, frame.s) - mx, y = Dot(d, frame.t) - my;
    cxx += a * x * x, cxy += a * x * y, cyy += a * y * y;
  }
  // Pseudo-inverse of the 2x2 covariance through its eigen decomposition: the value is
  // the weighted mean minus, along each eigenvector e, slope_e x (the mean's offset along e),
  // with slope_e = sum a (u_e - mean) b / lambda_e.
  const double half_trace = (cxx + cyy) / 2;
  const double root = std::hypot((cxx - cyy) / 2, cxy);
  const double lambda[2] = {half_trace + root, half_trace - root};
  const double angle = 0.5 * std::atan2(2 * cxy, cxx - cyy);
  const double ex[2] = {std::cos(angle), -std::sin(angle)};
  const double ey[2] = {std::sin(angle), std::cos(angle)};
  // A direction's slope moves the value by at most |offset| / spread times the values' range
  // (Cauchy-Schwarz on its weights); it is used only where that factor is at most
  // kMaxExtrapolation, so rounding noise (one patch: spreads of 1e-14) is never a spread.
  bool sloped[2];
  double along_mean[2];
  for (int e = 0; e < 2; ++e) {
    along_mean[e] = ex[e] * mx + ey[e] * my;  // the vertex is at 0
    sloped[e] =
        lambda[e] > 1e-6 * lambda[0] &&
        along_mean[e] * along_mean[e] * weight <= kMaxExtrapolation * kMaxExtrapolation * lambda[e];
  }
  for (size_t i = 0; i < fit.patches.size(); ++i) {
    const uint32_t p = fit.patches[i];
    const Vec3 d = mesh.patches[p].centroid - at;
    const double a = mesh.patches[p].area;
    const double x = Dot(d, frame.s) - mx, y = Dot(d, frame.t) - my;
    fit.weights[i] = a / weight;
    for (int e = 0; e < 2; ++e) {
      if (sloped[e]) fit.weights[i] -= a * (ex[e] * x + ey[e] * y) / lambda[e] * along_mean[e];
    }
  }
  return fit;
}

// Per welded vertex, the sum of its fit weights times `b` (one Rgb per patch).
std::vector<Rgb> ApplyFits(const std::vector<FitWeights>& fits, const std::vector<Rgb>& b) {
  std::vector<Rgb> values(fits.size(), Rgb{});
  for (size_t w = 0; w < fits.size(); ++w) {
    for (size_t i = 0; i < fits[w].patches.size(); ++i) {
      for (int k = 0; k < kBands; ++k)
        values[w][k] += fits[w].weights[i] * b[fits[w].patches[i]][k];
    }
  }
  return values;
}

}  // namespace

VertexFit::VertexFit(const PatchMesh& mesh, const ShadingMesh& shading)
    : mesh_(&mesh), shading_(&shading), fits_(shading.size()), means_(mesh, shading) {
  const JunctionPatches junctions(shading);
  ParallelFor(static_cast<int64_t>(shading.size()), 4096, 0, [&](int64_t begin, int64_t end) {
    std::vector<uint32_t> patches;
    for (auto w = static_cast<uint32_t>(begin); w < end; ++w) {
      FitPatches(mesh, shading, junctions, w, patches);
      fits_[w] = PlaneFitWeights(mesh, patches, mesh.positions[shading.representative[w]],
                                 shading.normals[w]);
    }
  });
}

absl::StatusOr<VertexFit> VertexFit::Build(const PatchMesh& mesh, const ShadingMesh& shading) {
  if (shading.welded.size() != mesh.positions.size()) {
    return absl::InvalidArgumentError("the shading mesh was built for another mesh");
  }
  return VertexFit(mesh, shading);
}

absl::StatusOr<std::vector<Rgb>> VertexFit::Welded(const std::vector<Rgb>& patch_radiosity) const {
  if (patch_radiosity.size() != mesh_->size()) {
    return absl::InvalidArgumentError(absl::StrCat("radiosity has ", patch_radiosity.size(),
                                                   " values for ", mesh_->size(), " patches"));
  }
  // The fit alone smooths: where B peaks (the middle of a lit wall) every patch's Gouraud
  // mean falls below its B, and a coarse wall's picture came out 2-3% dark. One correction
  // step fits the patches' deficits the same way and adds them, so the deficit left is
  // second order in the smoothing (and zero, as before, for a linear field).
  std::vector<Rgb> values = ApplyFits(fits_, patch_radiosity);
  means_.junctions.Apply(values);
  std::vector<Rgb> deficit = means_.Means(values);  // what Gouraud shading fails to carry
  for (size_t p = 0; p < deficit.size(); ++p) {
    for (int k = 0; k < kBands; ++k) deficit[p][k] = patch_radiosity[p][k] - deficit[p][k];
  }
  const std::vector<Rgb> correction = ApplyFits(fits_, deficit);
  for (size_t w = 0; w < values.size(); ++w) {
    for (int k = 0; k < kBands; ++k) values[w][k] = std::max(values[w][k] + correction[w][k], 0.0);
  }
  means_.junctions.Apply(values);
  // What the step leaves still moves light between neighbouring patches where B is curved
  // (under a lamp in a wall's plane, its second row of patches read 1.7% dark); the damped
  // matching takes all but 9% of the smooth part of it (gouraud_means.h).
  MatchPatchMeans(*mesh_, means_, patch_radiosity, values);
  return values;
}

absl::StatusOr<std::vector<Rgb>> VertexFit::AtPositions(
    const std::vector<Rgb>& patch_radiosity) const {
  auto welded = Welded(patch_radiosity);
  if (!welded.ok()) return welded.status();
  std::vector<Rgb> values(mesh_->positions.size());
  for (size_t i = 0; i < values.size(); ++i) values[i] = (*welded)[shading_->welded[i]];
  return values;
}

absl::StatusOr<std::vector<Rgb>> WeldedVertexRadiosity(const PatchMesh& mesh,
                                                       const ShadingMesh& shading,
                                                       const std::vector<Rgb>& patch_radiosity) {
  absl::StatusOr<VertexFit> fit = VertexFit::Build(mesh, shading);
  if (!fit.ok()) return fit.status();
  return fit->Welded(patch_radiosity);
}

absl::StatusOr<std::vector<Rgb>> VertexRadiosity(const PatchMesh& mesh, const ShadingMesh& shading,
                                                 const std::vector<Rgb>& patch_radiosity) {
  absl::StatusOr<VertexFit> fit = VertexFit::Build(mesh, shading);
  if (!fit.ok()) return fit.status();
  return fit->AtPositions(patch_radiosity);
}

}  // namespace radflux
