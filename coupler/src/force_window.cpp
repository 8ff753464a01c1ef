// The steady means of a coupled run; see force_window.hpp.
#include "coupler/force_window.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cosim/error.hpp"

namespace coupler {

namespace {

// The checkpoint's columns: one named array each (docs/reliability.md, "Coupled runs").
using RowField = double& (*)(ForceRow&);
const std::pair<const char*, RowField> kRowColumns[] = {
    {"time_s", [](ForceRow& r) -> double& { return r.time_s; }},
    {"traction_force_N", [](ForceRow& r) -> double& { return r.d.traction_force_N; }},
    {"motion_resistance_N", [](ForceRow& r) -> double& { return r.d.motion_resistance_N; }},
    {"groove_force_N", [](ForceRow& r) -> double& { return r.d.groove_force_N; }},
    {"vertical_pressure_force_N", [](ForceRow& r) -> double& { return r.d.vertical_pressure_force_N; }},
    {"rolling_resistance_moment_Nm", [](ForceRow& r) -> double& { return r.d.rolling_resistance_moment_Nm; }},
    {"pressure_centre_offset_m", [](ForceRow& r) -> double& { return r.d.pressure_centre_offset_m; }},
    {"rolling_resistance_force_N", [](ForceRow& r) -> double& { return r.d.rolling_resistance_force_N; }},
    {"drawbar_pull_N", [](ForceRow& r) -> double& { return r.d.drawbar_pull_N; }},
    {"net_longitudinal_pressure_force_N",
     [](ForceRow& r) -> double& { return r.d.net_longitudinal_pressure_force_N; }},
    {"traction_minus_rrf_N", [](ForceRow& r) -> double& { return r.d.traction_minus_rrf_N; }},
    {"sinkage_m", [](ForceRow& r) -> double& { return r.d.sinkage_m; }},
    {"contact_area_m2", [](ForceRow& r) -> double& { return r.d.contact_area_m2; }},
    {"rim_longitudinal_force_N", [](ForceRow& r) -> double& { return r.rim_longitudinal_force_N; }},
    {"contact_force_x_N", [](ForceRow& r) -> double& { return r.contact_force_x_N; }},
};

// Sums the drift's two halves of the rows in the window; `mid` splits them.
void add_drift(const std::deque<ForceRow>& rows, double window, double from, WindowDrift& drift) {
  const double mid = 0.5 * ((window > 0 ? from : rows.front().time_s) + rows.back().time_s);
  double first[WindowDrift::kCount] = {0}, second[WindowDrift::kCount] = {0};
  long n1 = 0, n2 = 0;
  for (const auto& r : rows) {
    if (window > 0 && r.time_s < from) continue;
    const double v[WindowDrift::kCount] = {
        r.d.traction_force_N,           r.d.motion_resistance_N,   r.d.groove_force_N,
        r.d.rolling_resistance_force_N, r.d.drawbar_pull_N,        r.d.sinkage_m,
        r.d.vertical_pressure_force_N,  r.rim_longitudinal_force_N};
    double* half = r.time_s < mid ? first : second;
    for (int k = 0; k < WindowDrift::kCount; ++k) half[k] += v[k];
    ++(r.time_s < mid ? n1 : n2);
  }
  for (int k = 0; k < WindowDrift::kCount; ++k)
    drift.second_less_first[k] = n1 && n2 ? second[k] / n2 - first[k] / n1 : 0.0;
}

}  // namespace

const std::array<const char*, WindowDrift::kCount> WindowDrift::names = {
    "traction_force_N",           "motion_resistance_N",     "groove_force_N",
    "rolling_resistance_force_N", "drawbar_pull_N",          "sinkage_m",
    "vertical_pressure_force_N",  "rim_longitudinal_force_N"};

bool steady_force(double mean_N, double drift_N) {
  return std::fabs(drift_N) <= std::max(kSteadyDriftShare * std::fabs(mean_N), kSteadyDriftFloor_N);
}

void ForceWindow::add(const ForceRow& row) {
  rows_.push_back(row);
  if (averaging_window_s_ > 0)  // the means read the rows of t >= the last t - window
    while (rows_.front().time_s < rows_.back().time_s - averaging_window_s_) rows_.pop_front();
}

void ForceWindow::save(cosim::CheckpointWriter& out, const std::string& prefix) const {
  for (const auto& [name, field] : kRowColumns) {
    std::vector<double> column;
    column.reserve(rows_.size());
    for (ForceRow r : rows_) column.push_back(field(r));
    out.put(prefix + name, column);
  }
}

void ForceWindow::restore(const cosim::CheckpointReader& in, const std::string& prefix) {
  const std::size_t count = in.get<double>(prefix + kRowColumns[0].first).size();
  rows_.assign(count, ForceRow{});
  for (const auto& [name, field] : kRowColumns) {
    const std::vector<double> column = in.get<double>(prefix + name, count);
    for (std::size_t i = 0; i < count; ++i) field(rows_[i]) = column[i];
  }
}

WindowMeans window_means(const ForceWindow& window_rows) {
  const std::deque<ForceRow>& rows = window_rows.rows();
  WindowMeans m;
  const double window = m.window_s = window_rows.averaging_window_s();
  const double from = rows.empty() ? 0.0 : rows.back().time_s - window;
  ForceDecomposition sum;
  double rim_fx = 0.0, contact_fx = 0.0;
  long n = 0;
  for (const auto& r : rows) {
    if (window > 0 && r.time_s < from) continue;
    if (n == 0) m.start_s = r.time_s;
    const auto& d = r.d;
    sum.traction_force_N += d.traction_force_N, sum.motion_resistance_N += d.motion_resistance_N;
    sum.groove_force_N += d.groove_force_N, sum.rolling_resistance_force_N += d.rolling_resistance_force_N;
    sum.drawbar_pull_N += d.drawbar_pull_N;
    sum.net_longitudinal_pressure_force_N += d.net_longitudinal_pressure_force_N;
    sum.traction_minus_rrf_N += d.traction_minus_rrf_N, sum.sinkage_m += d.sinkage_m;
    sum.rolling_resistance_moment_Nm += d.rolling_resistance_moment_Nm;
    sum.contact_area_m2 += d.contact_area_m2, sum.vertical_pressure_force_N += d.vertical_pressure_force_N;
    rim_fx += r.rim_longitudinal_force_N, contact_fx += r.contact_force_x_N;
    ++n;
  }
  m.count = n;
  if (n) m.end_s = rows.back().time_s;
  auto avg = [&](double v) { return n ? v / n : 0.0; };
  ForceDecomposition& mean = m.mean;
  mean.traction_force_N = avg(sum.traction_force_N), mean.motion_resistance_N = avg(sum.motion_resistance_N);
  mean.groove_force_N = avg(sum.groove_force_N);
  mean.rolling_resistance_moment_Nm = avg(sum.rolling_resistance_moment_Nm);
  mean.rolling_resistance_force_N = avg(sum.rolling_resistance_force_N), mean.drawbar_pull_N = avg(sum.drawbar_pull_N);
  mean.net_longitudinal_pressure_force_N = avg(sum.net_longitudinal_pressure_force_N);
  mean.traction_minus_rrf_N = avg(sum.traction_minus_rrf_N);
  mean.vertical_pressure_force_N = avg(sum.vertical_pressure_force_N);
  mean.sinkage_m = avg(sum.sinkage_m), mean.contact_area_m2 = avg(sum.contact_area_m2);
  m.rim_longitudinal_force_N = avg(rim_fx), m.contact_force_x_N = avg(contact_fx);
  m.has_drift = n >= 2;
  if (m.has_drift) add_drift(rows, window, from, m.drift);
  return m;
}

void put_window_results(const ForceWindow& window, nlohmann::json& results) {
  const WindowMeans m = window_means(window);
  results["averaging_window_s"] = m.window_s;
  if (m.count) results["averaging_window_start_s"] = m.start_s, results["averaging_window_end_s"] = m.end_s;
  results["averaged_steps"] = m.count;
  // Beside the decomposition's means, what a test rig would measure: the tyre's
  // longitudinal force on the rim, and the terrain's on the tyre (F2 + F3 - F1);
  // the drawbar pull is the latter less F5 (docs/force_decomposition.md,
  // "Drawbar pull and the rim's force").
  const std::pair<const char*, double> means[] = {
      {"traction_force_N", m.mean.traction_force_N},
      {"motion_resistance_N", m.mean.motion_resistance_N},
      {"groove_force_N", m.mean.groove_force_N},
      {"rolling_resistance_moment_Nm", m.mean.rolling_resistance_moment_Nm},
      {"rolling_resistance_force_N", m.mean.rolling_resistance_force_N},
      {"drawbar_pull_N", m.mean.drawbar_pull_N},
      {"rim_longitudinal_force_N", m.rim_longitudinal_force_N},
      {"terrain_longitudinal_force_N", m.contact_force_x_N},
      {"net_longitudinal_pressure_force_N", m.mean.net_longitudinal_pressure_force_N},
      {"traction_minus_rrf_N", m.mean.traction_minus_rrf_N},
      {"vertical_pressure_force_N", m.mean.vertical_pressure_force_N},
      {"sinkage_m", m.mean.sinkage_m},
      {"contact_area_m2", m.mean.contact_area_m2}};
  for (const auto& [name, value] : means) results[name] = value;
  if (m.has_drift) {
    nlohmann::json drift, unsteady = nlohmann::json::array();
    for (int k = 0; k < WindowDrift::kCount; ++k) {
      const char* name = WindowDrift::names[k];
      const double d = m.drift.second_less_first[k];
      drift[name] = d;
      // Every force of the window must be steady; the sinkage's drift is reported, not judged.
      if (std::string(name) != "sinkage_m" && !steady_force(results[name].get<double>(), d)) unsteady.push_back(name);
    }
    results["window_drift"] = drift;
    results["window_steady"] = unsteady.empty();
    results["unsteady_forces"] = unsteady;
  }
  if (!window.rows().empty()) {
    results["final_contact_area_m2"] = window.rows().back().d.contact_area_m2;
    results["final_sinkage_m"] = window.rows().back().d.sinkage_m;
  }
}

}  // namespace coupler
