// The end-of-run report of a coupled run; see run_report.hpp.
#include "run_report.hpp"

#include <cstdio>
#include <utility>

#include "cosim/result_references.hpp"
#include "run_energy.hpp"

namespace cosim {
namespace {

bool named_unsteady(const nlohmann::json& r, const char* key) {
  if (!r.contains("unsteady_forces")) return false;
  for (const auto& name : r["unsteady_forces"])
    if (name == key) return true;
  return false;
}

// The force decomposition of thesis ch. 2, a force whose mean still moves across
// the window (coupler: drift above 5 % or 20 N) marked with its drift.
void print_forces(const nlohmann::json& r) {
  if (!r.contains("traction_force_N")) return;
  std::printf("\nForce decomposition (thesis ch. 2), means over the last %.3g s:\n",
              r.value("averaging_window_s", 0.0));
  const std::pair<const char*, const char*> rows[] = {
      {"traction_force_N", "traction F3"},
      {"motion_resistance_N", "motion resistance F1"},
      {"groove_force_N", "groove force F2"},
      {"rolling_resistance_force_N", "rolling-resistance force F5"},
      {"drawbar_pull_N", "drawbar pull F2 + F3 - F1 - F5"},
      {"rim_longitudinal_force_N", "tyre on the rim, along x"},
      {"net_longitudinal_pressure_force_N", "net longitudinal pressure -F1 + F2"},
      {"vertical_pressure_force_N", "vertical pressure force F4"}};
  for (const auto& [key, label] : rows) {
    if (!r.contains(key)) continue;
    std::printf("  %-38s %10.1f N", label, r[key].get<double>());
    if (named_unsteady(r, key))
      std::printf("   not steady: %+.0f N from the window's first half to its second",
                  r["window_drift"][key].get<double>());
    std::printf("\n");
  }
  if (r.contains("sinkage_m")) std::printf("  %-38s %10.1f mm\n", "sinkage", 1e3 * r["sinkage_m"].get<double>());
  if (r.contains("contact_area_m2"))
    std::printf("  %-38s %10.4f m^2\n", "contact area", r["contact_area_m2"].get<double>());
  if (r.contains("window_steady"))
    std::printf("  %s\n", r["window_steady"].get<bool>()
                              ? "the window is steady: every force drifts by less than 5 % of its mean or 20 N"
                              : "the window is NOT steady for the forces marked: their means are not a steady state");
}

}  // namespace

void print_run_report(const RunReportInputs& in) {
  print_forces(in.results);
  // The split tables and the motion resistance's work beside the plastic work (run_energy.hpp).
  std::printf("%s", coupled_run_energy_text(in.summary.value("energy", nlohmann::json())).c_str());
  std::printf("%s", reference_lines(in.summary.value("comparison", nlohmann::json())).c_str());
  const nlohmann::json& p = in.performance;
  if (p.contains("coupling_window_s"))
    std::printf("\ncoupling window %.3g s, %d tyre sub-steps, active particles %.0f %%, wall time %.0f s\n",
                p["coupling_window_s"].get<double>(), p.value("tyre_substeps", 1),
                100.0 * p.value("active_particle_share", 1.0), in.summary.value("wall_time_s", 0.0));
  std::printf("every result: %s\n", in.summary_path.c_str());
}

}  // namespace cosim
