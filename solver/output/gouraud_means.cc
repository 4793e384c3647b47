#include "solver/output/gouraud_means.h"

#include <algorithm>
#include <cmath>

namespace radflux {
namespace {

// The damping of MatchPatchMeans: moving a vertex costs this times what the same error in the
// mean of a patch of the vertex's carried area costs. A smooth deficit (light moved from one
// row of patches to the next) is then removed but for kDamping / (1 + kDamping), 9%; the rough
// patterns that the rows' noise asks for (one patch above its neighbours), which vertex values
// can only follow by large swings, cost more than they fix and keep the fit's smoothing (at
// 1e-4 the Cornell box's ceiling showed each patch's noise as a blotch).
constexpr double kDamping = 0.1;
// Conjugate gradient stops at this residual, relative to its start, or after kMaxIterations
// (the damping bounds the condition number): the Cornell box's 2,082 patches take 8 and the
// conference room's 398,882 take 26 (1.0 s at load 11; 73 and 2.8 s at 1e-6, with the same
// Cornell picture means to 0.001%).
constexpr double kTolerance = 1e-2;
constexpr int kMaxIterations = 100;

using Field = std::vector<Rgb>;

Rgb Dot(const Field& a, const Field& b) {
  Rgb sum{};
  for (size_t i = 0; i < a.size(); ++i) {
    for (int k = 0; k < kBands; ++k) sum[k] += a[i][k] * b[i][k];
  }
  return sum;
}

// The transpose of GouraudMeans::Means with each shown patch's value times its area (hidden
// patches: 0), added into `out`: the least squares' weighted adjoint.
void AddWeightedTranspose(const PatchMesh& mesh, const GouraudMeans& means, const Field& per_patch,
                          Field& out) {
  for (size_t p = 0; p < means.patches.size(); ++p) {
    const double area = mesh.patches[p].hidden ? 0.0 : mesh.patches[p].area;
    const PatchMeanWeights& w = means.patches[p];
    for (int c = 0; c < w.n; ++c) {
      for (int k = 0; k < kBands; ++k) out[w.welded[c]][k] += area * w.weight[c] * per_patch[p][k];
    }
  }
}

}  // namespace

PatchMeanWeights GouraudMeanWeights(const PatchMesh& mesh, const ShadingMesh& shading, uint32_t p) {
  const Patch& patch = mesh.patches[p];
  PatchMeanWeights out;
  out.n = patch.VertexCount();
  for (int c = 0; c < out.n; ++c) out.welded[c] = shading.welded[patch.v[c]];
  if (out.n == 3) {
    out.weight = {1.0 / 3, 1.0 / 3, 1.0 / 3, 0};
    return out;
  }
  // x(s, t) = bilinear in the corners; on a planar quad |x_s x x_t| is bilinear in (s, t), so
  // 2 x 2 Gauss points integrate each corner's weight times it exactly.
  const Vec3 p0 = mesh.Vertex(p, 0), p1 = mesh.Vertex(p, 1), p2 = mesh.Vertex(p, 2),
             p3 = mesh.Vertex(p, 3);
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  double total = 0;
  for (double s : g) {
    for (double t : g) {
      const Vec3 xs = (p1 - p0) * (1 - t) + (p2 - p3) * t;
      const Vec3 xt = (p3 - p0) * (1 - s) + (p2 - p1) * s;
      const double j = Length(Cross(xs, xt));
      const double phi[4] = {(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t};
      for (int c = 0; c < 4; ++c) out.weight[c] += phi[c] * j;
      total += j;
    }
  }
  if (!(total > 0)) {
    out.weight = {0.25, 0.25, 0.25, 0.25};
    return out;
  }
  for (double& w : out.weight) w /= total;
  return out;
}

TJunctionMap::TJunctionMap(const PatchMesh& mesh, const ShadingMesh& shading) {
  std::vector<std::pair<double, size_t>> order;
  for (size_t i = 0; i < shading.t_junctions.size(); ++i) {
    const TJunction& j = shading.t_junctions[i];
    const Patch& patch = mesh.patches[j.patch];
    const Vec3 a = mesh.positions[patch.v[j.edge]];
    const Vec3 b = mesh.positions[patch.v[(j.edge + 1) % patch.VertexCount()]];
    order.push_back({-Length(b - a), i});
  }
  std::sort(order.begin(), order.end());
  for (const auto& [unused, i] : order) {
    const TJunction& j = shading.t_junctions[i];
    const Patch& patch = mesh.patches[j.patch];
    steps_.push_back({j.vertex, shading.welded[patch.v[j.edge]],
                      shading.welded[patch.v[(j.edge + 1) % patch.VertexCount()]], j.t});
  }
}

void TJunctionMap::Apply(std::vector<Rgb>& values) const {
  for (const Step& s : steps_) {
    for (int k = 0; k < kBands; ++k) {
      values[s.vertex][k] = (1 - s.t) * values[s.a][k] + s.t * values[s.b][k];
    }
  }
}

void TJunctionMap::ApplyTransposed(std::vector<Rgb>& values) const {
  for (auto s = steps_.rbegin(); s != steps_.rend(); ++s) {
    const Rgb moved = values[s->vertex];
    values[s->vertex] = Rgb{};
    for (int k = 0; k < kBands; ++k) {
      values[s->a][k] += (1 - s->t) * moved[k];
      values[s->b][k] += s->t * moved[k];
    }
  }
}

GouraudMeans::GouraudMeans(const PatchMesh& mesh, const ShadingMesh& shading)
    : junctions(mesh, shading) {
  patches.reserve(mesh.size());
  for (uint32_t p = 0; p < mesh.size(); ++p)
    patches.push_back(GouraudMeanWeights(mesh, shading, p));
}

std::vector<Rgb> GouraudMeans::Means(const std::vector<Rgb>& values) const {
  std::vector<Rgb> means(patches.size(), Rgb{});
  for (size_t p = 0; p < patches.size(); ++p) {
    for (int c = 0; c < patches[p].n; ++c) {
      for (int k = 0; k < kBands; ++k)
        means[p][k] += patches[p].weight[c] * values[patches[p].welded[c]][k];
    }
  }
  return means;
}

void MatchPatchMeans(const PatchMesh& mesh, const GouraudMeans& means, const std::vector<Rgb>& b,
                     std::vector<Rgb>& values) {
  const size_t nv = values.size();
  const TJunctionMap& junctions = means.junctions;
  std::vector<double> carried(nv, 0), diagonal(nv, 0);
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const double weight = mesh.patches[p].hidden ? 0.0 : mesh.patches[p].area;
    const PatchMeanWeights& w = means.patches[p];
    for (int c = 0; c < w.n; ++c) {
      carried[w.welded[c]] += mesh.patches[p].area * w.weight[c];
      diagonal[w.welded[c]] += weight * w.weight[c] * w.weight[c];
    }
  }
  double mean_carried = 0;
  for (double a : carried) mean_carried += a / static_cast<double>(nv);
  for (size_t v = 0; v < nv; ++v) {
    if (!(carried[v] > 0)) carried[v] = mean_carried;
    diagonal[v] += kDamping * carried[v];
  }
  // H x = T' M' W M T x + damping C x, the normal equations of the change x; solved by
  // conjugate gradient with H's diagonal (without T) as the preconditioner, per band.
  const auto apply_h = [&](const Field& x) {
    Field tx = x;
    junctions.Apply(tx);
    Field out(nv, Rgb{});
    AddWeightedTranspose(mesh, means, means.Means(tx), out);
    junctions.ApplyTransposed(out);
    for (size_t v = 0; v < nv; ++v) {
      for (int k = 0; k < kBands; ++k) out[v][k] += kDamping * carried[v] * x[v][k];
    }
    return out;
  };
  Field residual(nv, Rgb{});
  {
    Field deficit = means.Means(values);
    for (size_t p = 0; p < deficit.size(); ++p) {
      for (int k = 0; k < kBands; ++k) deficit[p][k] = b[p][k] - deficit[p][k];
    }
    AddWeightedTranspose(mesh, means, deficit, residual);
    junctions.ApplyTransposed(residual);
  }
  const auto precondition = [&](const Field& r) {
    Field z = r;
    for (size_t v = 0; v < nv; ++v) {
      for (int k = 0; k < kBands; ++k) z[v][k] /= diagonal[v];
    }
    return z;
  };
  Field change(nv, Rgb{}), z = precondition(residual), direction = z;
  Rgb rz = Dot(residual, z);
  const Rgb start = rz;
  for (int it = 0; it < kMaxIterations; ++it) {
    bool done = true;
    for (int k = 0; k < kBands; ++k) done = done && !(rz[k] > kTolerance * kTolerance * start[k]);
    if (done) break;
    const Field hd = apply_h(direction);
    const Rgb dhd = Dot(direction, hd);
    Rgb alpha{};
    for (int k = 0; k < kBands; ++k) alpha[k] = dhd[k] > 0 ? rz[k] / dhd[k] : 0;
    for (size_t v = 0; v < nv; ++v) {
      for (int k = 0; k < kBands; ++k) {
        change[v][k] += alpha[k] * direction[v][k];
        residual[v][k] -= alpha[k] * hd[v][k];
      }
    }
    z = precondition(residual);
    const Rgb next = Dot(residual, z);
    for (size_t v = 0; v < nv; ++v) {
      for (int k = 0; k < kBands; ++k) {
        const double beta = rz[k] > 0 ? next[k] / rz[k] : 0;
        direction[v][k] = z[v][k] + beta * direction[v][k];
      }
    }
    rz = next;
  }
  for (size_t v = 0; v < nv; ++v) {
    for (int k = 0; k < kBands; ++k) values[v][k] = std::max(values[v][k] + change[v][k], 0.0);
  }
  junctions.Apply(values);
}

}  // namespace radflux
