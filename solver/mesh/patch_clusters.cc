#include "solver/mesh/patch_clusters.h"

#include <algorithm>

namespace radflux {

PatchClusters ClustersFromAssignment(const PatchMesh& mesh, std::vector<uint32_t> of_patch,
                                     uint32_t count) {
  PatchClusters c;
  c.first.assign(count + 1, 0);
  c.area.assign(count, 0.0);
  for (uint32_t p = 0; p < of_patch.size(); ++p) {
    ++c.first[of_patch[p] + 1];
    c.area[of_patch[p]] += mesh.patches[p].area;
  }
  for (uint32_t u = 0; u < count; ++u) c.first[u + 1] += c.first[u];
  c.members.resize(of_patch.size());
  std::vector<uint32_t> next(c.first.begin(), c.first.end() - 1);
  for (uint32_t p = 0; p < of_patch.size(); ++p) c.members[next[of_patch[p]]++] = p;
  c.of_patch = std::move(of_patch);
  return c;
}

PatchAttributes ComputeClusterAttributes(const Scene& scene, const PatchMesh& mesh,
                                         const PatchClusters& clusters) {
  PatchAttributes out;
  const size_t n = clusters.size();
  out.area.reserve(n);
  out.reflectance.reserve(n);
  out.emission.reserve(n);
  for (uint32_t u = 0; u < n; ++u) {
    const Patch& patch = mesh.patches[clusters.members[clusters.first[u]]];
    const Material& m = scene.materials[scene.faces[patch.face].material];
    out.area.push_back(clusters.area[u] * m.opacity);
    out.reflectance.push_back(m.reflectance);
    out.emission.push_back(m.emission);
    out.grey = out.grey && IsGrey(m.reflectance) && IsGrey(m.emission);
  }
  return out;
}

std::vector<Rgb> PushDownToPatches(const PatchClusters& clusters, const std::vector<Rgb>& b) {
  std::vector<Rgb> out(clusters.of_patch.size());
  for (size_t p = 0; p < out.size(); ++p) out[p] = b[clusters.of_patch[p]];
  return out;
}

UnknownPointSampler::UnknownPointSampler(const PatchMesh& mesh, const PatchClusters* clusters,
                                         uint32_t u)
    : mesh_(mesh) {
  if (clusters == nullptr || clusters->empty()) {
    members_.push_back(u);
  } else {
    const std::span<const uint32_t> m = clusters->Members(u);
    members_.assign(m.begin(), m.end());
  }
  samplers_.reserve(members_.size());
  cdf_.reserve(members_.size());
  double total = 0;
  for (uint32_t p : members_) {
    samplers_.emplace_back(mesh, p);
    total += mesh.patches[p].area;
    cdf_.push_back(total);
  }
  for (double& c : cdf_) c = total > 0 ? c / total : 1;
  cdf_.back() = 1;
}

std::pair<size_t, double> UnknownPointSampler::Member(double ux) const {
  if (cdf_.size() == 1) return {0, ux};
  const size_t m = static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end() - 1, ux) -
                                       cdf_.begin());
  const double lo = m > 0 ? cdf_[m - 1] : 0;
  const double width = cdf_[m] - lo;
  return {m, width > 0 ? std::min((ux - lo) / width, 0x1.fffffffffffffp-1) : 0.0};
}

SurfacePoint UnknownPointSampler::operator()(Point2 u) const {
  const auto [m, x] = Member(u.x);
  return {samplers_[m]({x, u.y}), mesh_.patches[members_[m]].normal};
}

}  // namespace radflux
