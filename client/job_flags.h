// The job options of `radflux solve` and `radflux submit` as command-line flags: one
// definition so both verbs accept exactly the same spelling (a contract scripts use).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "absl/status/statusor.h"
#include "solver/pipeline.h"

namespace radflux::cli {

struct JobFlags {
  int64_t patches = 0;
  double max_edge = 0;
  std::string form_factors = "monte_carlo";
  int rays = 0, hemicube_res = 0, samples = 0;  // 0: the method's default
  double cutoff = -1;                           // < 0: default
  std::string solver = "auto";                  // gauss_seidel, or cg when some rho > 0.9
  double tolerance = 1e-4;
  int max_iterations = 1000;
  int threads = 0;
  uint64_t seed = 1;
  // --solver hierarchical: BFA refinement threshold, the cluster hierarchy above the faces, the
  // smallest element as a fraction of the scene's area.
  double link_epsilon = HierarchicalOptions{}.link_epsilon;
  std::string clusters = "on";
  double min_element_area = HierarchicalOptions{}.min_area_fraction;
  int adaptive_passes = 0;  // adaptive meshing passes after the first solve
  double adaptive_threshold = 0.1;
};

// The scene's patch count when neither --patches nor --max-edge is given.
inline constexpr int64_t kDefaultPatches = 2000;

void AddJobFlags(CLI::App& app, JobFlags& flags);
absl::StatusOr<JobOptions> ToJobOptions(const JobFlags& flags);

}  // namespace radflux::cli
