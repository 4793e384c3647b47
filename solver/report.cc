#include "solver/report.h"

#include <algorithm>
#include <string>

#include "absl/strings/str_format.h"
#include "solver/core/parallel.h"

namespace radflux {
namespace {

nlohmann::json BandsJson(const Rgb& c) { return {c[0], c[1], c[2]}; }

nlohmann::json OptionsJson(const JobOptions& o) {
  const FormFactorOptions& f = o.form_factors;
  nlohmann::json options = {{"patches", o.mesh.target_patches},
                            {"max_edge", o.mesh.max_edge},
                            {"form_factors", std::string(MethodName(f.method))},
                            {"rays", f.rays},
                            {"hemicube_res", f.hemicube_res},
                            {"samples", f.samples},
                            {"cutoff", f.cutoff},
                            {"seed", f.seed},
                            {"solver", std::string(SolverName(o.solver.method))},
                            {"tolerance", o.solver.tolerance},
                            {"max_iterations", o.solver.max_iterations}};
  if (o.hierarchical.enabled) {
    options["solver"] = "hierarchical";
    options["link_epsilon"] = o.hierarchical.link_epsilon;
    options["clusters"] = o.hierarchical.clusters;
    options["min_element_area"] = o.hierarchical.min_area_fraction;
  }
  if (o.adaptive.passes > 0) {
    options["adaptive_passes"] = o.adaptive.passes;
    options["adaptive_threshold"] = o.adaptive.threshold;
  }
  return options;
}

// Hierarchical radiosity's elements and links: its memory against n (leaves).
nlohmann::json HierarchicalJson(const HierarchicalStats& s) {
  return {{"faces", s.roots},
          {"clusters", s.clusters},
          {"elements", s.elements},
          {"leaves", s.leaves},
          {"patches", s.patches},
          {"initial_links", s.initial_links},
          {"links", s.links},
          {"link_bytes", s.link_bytes},
          {"element_bytes", s.element_bytes},
          {"links_per_leaf",
           s.leaves > 0 ? static_cast<double>(s.links) / static_cast<double>(s.leaves) : 0.0},
          {"passes", s.passes},
          {"refine_rounds", s.refine_rounds},
          {"refine_seconds", s.refine_seconds},
          {"gather_seconds", s.solve_seconds}};
}

// One entry per adaptive pass (0: the first solve on the coarse mesh).
nlohmann::json AdaptiveJson(const std::vector<AdaptivePass>& passes) {
  nlohmann::json out = nlohmann::json::array();
  for (const AdaptivePass& p : passes) {
    out.push_back({{"patches", p.patches},
                   {"split", p.split},
                   {"rows_recomputed", p.rows_recomputed},
                   {"entries_computed", p.entries_computed},
                   {"seconds", p.seconds},
                   {"change_in_b", p.change_in_b}});
  }
  return out;
}

// The balance with its threshold; when it is not ok, which term is out and why.
nlohmann::json BalanceJson(const absl::StatusOr<EnergyBalance>& balance) {
  if (!balance.ok()) return {{"error", std::string(balance.status().message())}};
  const EnergyBalance& e = *balance;
  Rgb imbalance{};
  for (int b = 0; b < kBands; ++b) {
    imbalance[b] = e.Imbalance(b);
  }
  nlohmann::json out = {
      {"emitted", BandsJson(e.emitted)},
      {"absorbed", BandsJson(e.absorbed)},
      {"escaped", BandsJson(e.escaped)},
      {"scaled_off", BandsJson(e.scaled_off)},
      {"cell_detail", BandsJson(e.cell_detail)},
      {"relative_scaled_off", e.RelativeScaledOff()},
      {"imbalance", BandsJson(imbalance)},
      {"noise", BandsJson(e.noise)},
      {"relative_imbalance", e.RelativeImbalance()},
      {"tolerance", e.Tolerance()},
      {"tolerance_rule",
       absl::StrFormat("min(%g, max(%g, %g noise / emitted)); noise: the standard "
                       "deviation of the imbalance the rows' Monte Carlo noise gives "
                       "(multinomial rows of k rays; light samples measured against the "
                       "emitters' own rows); ok when both |imbalance| and scaled_off "
                       "(the row-sum cap's removed power) are within it",
                       kEnergyBalanceCeiling, kEnergyBalanceFloor, kEnergyBalanceSigmas)},
      {"ok", e.Ok()}};
  if (!e.Ok()) out["why"] = e.Why();
  return out;
}

// What cg handed over and why, with the solve's estimated remaining error.
nlohmann::json SolverJson(const SolveResult& s) {
  nlohmann::json used = nlohmann::json::array();
  for (SolverMethod m : s.methods_used) used.push_back(std::string(SolverName(m)));
  return {{"requested", std::string(SolverName(s.requested))},
          {"used", used},
          {"fallback_reason", s.fallback_reason.empty() ? nlohmann::json(nullptr)
                                                        : nlohmann::json(s.fallback_reason)}};
}

// Power the cut-off dropped, W per band: the dropped form-factor area sum_i A_i d_i times
// the area-mean radiosity (an estimate: the dropped entries' own B_j are not kept).
nlohmann::json DroppedPowerJson(const JobResult& result) {
  const std::vector<Patch>& p = result.job->mesh.patches;  // B is per patch here
  const std::vector<Rgb>& b = result.solve.radiosity;
  Rgb mean{};
  double area = 0;
  for (size_t i = 0; i < b.size() && i < p.size(); ++i) {
    area += p[i].area;
    for (int k = 0; k < kBands; ++k) mean[k] += p[i].area * b[i][k];
  }
  Rgb watts{};
  for (int k = 0; k < kBands; ++k)
    watts[k] = area > 0 ? result.row_stats.dropped_area * mean[k] / area : 0;
  return BandsJson(watts);
}

// The unknowns against the faces and patches: how many groups of patches (face_grouping.h)
// the solve had, and their sizes.
nlohmann::json UnknownsJson(const JobResult& result) {
  const PreparedJob& job = *result.job;
  const PatchClusters& c = job.clusters;
  size_t groups = 0, grouped = 0, largest = c.empty() ? 1 : 0;
  for (uint32_t u = 0; u < c.size(); ++u) {
    const size_t members = c.Members(u).size();
    largest = std::max(largest, members);
    if (members > 1) {
      ++groups;
      grouped += members;
    }
  }
  // The unknowns partly enclosed in a solid (exposed_area.h) and their enclosed area's share.
  size_t partly_enclosed = 0;
  double enclosed = 0, total = 0;
  for (uint32_t u = 0; u < job.rows.opaque_area.size(); ++u) {
    total += job.rows.opaque_area[u];
    if (job.rows.Exposure(u) >= 1) continue;
    ++partly_enclosed;
    enclosed += job.rows.opaque_area[u] * (1 - job.rows.Exposure(u));
  }
  return {{"unknowns", job.Unknowns()},
          {"partly_enclosed", partly_enclosed},
          {"enclosed_area_share", total > 0 ? enclosed / total : 0.0},
          {"grouped", !c.empty()},
          {"groups", groups},
          {"grouped_patches", grouped},
          {"largest_group", largest},
          {"direct_cells", job.cells.size()},
          {"direct_cells_sampled", result.direct_cells},
          {"direct_cells_kept", result.direct_kept},
          {"direct_rays", result.direct_rays},
          {"cell_detail_rays", result.detail_rays},
          {"cell_detail_indirect_cells", result.detail_indirect_cells},
          {"direct_lifted_patches", result.direct_lifted}};
}

// Where the rows lived when they spilled (before the report's own pass over them).
nlohmann::json SpillJson(const RowStore& store, const JobOptions& options) {
  const RowReadStats& read = store.read_stats();
  return {{"memory_limit", options.spill.memory_limit},
          {"memory_bytes", store.MemoryBytes()},
          {"spilled_bytes", store.SpilledBytes()},
          {"read_passes", read.passes},
          {"read_bytes", read.bytes},
          {"read_seconds", read.read_seconds},
          {"wait_seconds", read.wait_seconds}};
}

// Every change import made to the scene, one entry per kind (scene.import_log).
nlohmann::json ImportJson(const ImportLog& log) {
  nlohmann::json fixups = nlohmann::json::array();
  for (const ImportFixup& f : log.fixups()) {
    nlohmann::json fixup = {
        {"kind", f.kind}, {"message", f.Text()}, {"count", f.count}, {"first", f.first}};
    if (!f.share_of.empty()) {
      fixup["share"] = {{"mean", f.ShareMean()}, {"max", f.share_max}};
    }
    fixups.push_back(fixup);
  }
  return fixups;
}

}  // namespace

const absl::StatusOr<EnergyBalance>& SettleEnergyBalance(JobResult& result,
                                                         const JobOptions& options) {
  if (!result.solved_balance) {
    result.solved_balance =
        StreamEnergyBalance(result.System(), result.solve.radiosity,
                            result.Sampling(options.form_factors), result.row_stats.scaled_off);
  }
  return *result.solved_balance;
}

nlohmann::json MakeJobReport(JobResult& result, const JobOptions& options,
                             const std::string& scene_name) {
  const absl::StatusOr<EnergyBalance>& balance = SettleEnergyBalance(result, options);
  const PreparedJob& job = *result.job;
  const JobTimings& t = result.timings;
  nlohmann::json spill = nullptr;
  if (result.row_store != nullptr) spill = SpillJson(*result.row_store, options);
  const int threads = ThreadCount(options.form_factors.threads);
  nlohmann::json report = {
      {"scene", scene_name},
      {"options", OptionsJson(options)},
      {"import", ImportJson(job.scene.import_log)},
      {"threads", threads},
      {"mesh",
       {{"faces", job.scene.faces.size()},
        {"patches", job.mesh_stats.patches},
        {"unknowns", UnknownsJson(result)},
        {"min_area", job.mesh_stats.min_area},
        {"max_area", job.mesh_stats.max_area},
        {"max_aspect", job.mesh_stats.max_aspect}}},
      {"matrix",
       {{"nnz", result.RowNonZeros()},
        {"bytes", result.RowBytes()},
        {"spill", spill},
        {"dropped_sum", result.row_stats.dropped_sum},
        {"max_row_dropped", result.row_stats.max_row_dropped},
        {"dropped_power_estimate", DroppedPowerJson(result)}}},
      {"seconds",
       {{"mesh", t.mesh},
        {"embree", t.embree},
        {"rows", t.rows},
        {"solve", t.solve},
        {"direct", t.direct}}},
      {"rays", result.row_stats.rays},
      {"rays_per_second", t.rows > 0 ? result.row_stats.rays / t.rows : 0.0},
      {"solve",
       {{"method", std::string(SolverName(result.solve.method))},
        {"iterations", result.solve.iterations},
        {"residual", result.solve.residual},
        {"residual_measure", "||E + rho F B - B|| / ||rho F B|| (area-weighted), max over bands"},
        {"error_estimate", result.solve.error_estimate},
        {"error_estimate_method", result.solve.error_estimate_method},
        {"converged", result.solve.converged},
        {"cancelled", result.solve.cancelled},
        {"bands_solved", result.solve.bands_solved},
        {"reciprocity_error", result.solve.reciprocity_error},
        {"residual_history", result.solve.residual_history}}},
      {"solver", SolverJson(result.solve)},
      {"energy_balance", BalanceJson(balance)},
  };
  if (result.hierarchical) report["hierarchical"] = HierarchicalJson(*result.hierarchical);
  if (!result.adaptive_passes.empty()) report["adaptive"] = AdaptiveJson(result.adaptive_passes);
  return report;
}

}  // namespace radflux
