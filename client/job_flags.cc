#include "client/job_flags.h"

namespace radflux::cli {

void AddJobFlags(CLI::App& app, JobFlags& f) {
  auto* patches = app.add_option(
      "--patches", f.patches,
      "target number of unknowns: patches, or groups of small faces when the scene has more "
      "faces (default " + std::to_string(kDefaultPatches) + ")");
  app.add_option("--max-edge", f.max_edge, "or: longest patch edge, scene units")
      ->excludes(patches);
  app.add_option("--form-factors", f.form_factors, "form-factor method")
      ->check(CLI::IsMember({"monte_carlo", "hemicube", "analytic"}))
      ->capture_default_str();
  app.add_option("--rays", f.rays, "monte_carlo: rays per patch k (default 64)");
  app.add_option("--hemicube-res", f.hemicube_res, "hemicube: top-face resolution r (default 32)");
  app.add_option(
      "--samples", f.samples,
      "analytic: points per patch s; monte_carlo: 16 s light samples per row for emitter "
      "columns, at 4 s points (default 4)");
  app.add_option("--cutoff", f.cutoff, "drop form factors below this (default 1e-6)");
  app.add_option("--solver", f.solver, "linear solver")
      ->check(CLI::IsMember(
          {"auto", "jacobi", "gauss_seidel", "southwell", "cg", "direct", "hierarchical"}))
      ->capture_default_str();
  app.add_option("--tolerance", f.tolerance, "stop at this relative residual")
      ->capture_default_str();
  app.add_option("--max-iterations", f.max_iterations, "stop after this many sweeps")
      ->capture_default_str();
  app.add_option("--threads", f.threads, "threads (0 = all cores)")->capture_default_str();
  app.add_option("--link-epsilon", f.link_epsilon,
                 "hierarchical: refine links with rho*B*F*A above this fraction of emitted power")
      ->capture_default_str();
  app.add_option("--clusters", f.clusters,
                 "hierarchical: clusters above the faces (off: every pair of faces starts linked)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--min-element-area", f.min_element_area,
                 "hierarchical: no element smaller than this fraction of the scene's area")
      ->capture_default_str();
  app.add_option(
         "--adaptive-passes", f.adaptive_passes,
         "adaptive meshing: refinement passes after the first solve (rows by --form-factors)")
      ->capture_default_str();
  app.add_option("--adaptive-threshold", f.adaptive_threshold,
                 "adaptive meshing: split where neighbours' B differ by more than this fraction of "
                 "the mean B")
      ->capture_default_str();
  app.add_option("--seed", f.seed, "job seed; samples are seeded per patch from it")
      ->capture_default_str();
}

absl::StatusOr<JobOptions> ToJobOptions(const JobFlags& f) {
  JobOptions o;
  o.mesh.max_edge = f.max_edge;
  o.mesh.target_patches = f.max_edge > 0 ? 0 : (f.patches > 0 ? f.patches : kDefaultPatches);
  if (f.patches < 0) o.mesh.target_patches = f.patches;  // refused by validation below
  o.form_factors.method = *ParseMethod(f.form_factors);
  if (f.rays != 0) o.form_factors.rays = f.rays;
  if (f.hemicube_res != 0) o.form_factors.hemicube_res = f.hemicube_res;
  if (f.samples != 0) o.form_factors.samples = f.samples;
  if (f.cutoff >= 0) o.form_factors.cutoff = f.cutoff;
  o.form_factors.threads = f.threads;
  o.form_factors.seed = f.seed;
  o.hierarchical.enabled = f.solver == "hierarchical";
  o.hierarchical.link_epsilon = f.link_epsilon;
  o.hierarchical.clusters = f.clusters == "on";
  o.hierarchical.min_area_fraction = f.min_element_area;
  o.adaptive.passes = f.adaptive_passes;
  o.adaptive.threshold = f.adaptive_threshold;
  o.solver.method = o.hierarchical.enabled ? SolverMethod::kJacobi : *ParseSolver(f.solver);
  o.solver.tolerance = f.tolerance;
  o.solver.max_iterations = f.max_iterations;
  o.solver.threads = f.threads;
  if (absl::Status s = ValidateJobOptions(o); !s.ok()) return s;
  return o;
}

}  // namespace radflux::cli
