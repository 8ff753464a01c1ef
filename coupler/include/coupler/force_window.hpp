#pragma once
// The steady means of a coupled run: the force decomposition averaged over the
// last averaging window of the run (thesis 6.1: results "taken at the steady
// state region"), with how much each mean drifts across the window.
//
// Each mean is the rows' values summed in row order and divided once by their
// count (every exchange counts the same: the windows are of equal length).
#include <array>
#include <cstdint>
#include <deque>
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/checkpoint.hpp"
#include "coupler/forces.hpp"

namespace coupler {

// One exchange's forces, as the means need them.
struct ForceRow {
  double time_s = 0.0;
  ForceDecomposition d;
  double rim_longitudinal_force_N = 0.0;  // the tyre's force on the rim, forward +
  double contact_force_x_N = 0.0;         // the terrain's force on the tyre (F2 + F3 - F1)
};

// The rows of the last averaging_window_s of the run (all of them if it is 0):
// what the means need; memory stays flat over a long run.
class ForceWindow {
 public:
  explicit ForceWindow(double averaging_window_s = 0.0) : averaging_window_s_(averaging_window_s) {}

  // Appends a row and drops those older than the last row's time less the window.
  void add(const ForceRow& row);
  double averaging_window_s() const { return averaging_window_s_; }
  const std::deque<ForceRow>& rows() const { return rows_; }

  // The rows as one named array per column under `prefix` ("<prefix>time_s", ...),
  // and back; restore throws cosim::Error if the columns differ in length.
  void save(cosim::CheckpointWriter& out, const std::string& prefix) const;
  void restore(const cosim::CheckpointReader& in, const std::string& prefix);

 private:
  double averaging_window_s_;
  std::deque<ForceRow> rows_;
};

// Each mean over its window's second half less that over its first half: a
// steady state gives the noise only, a transient a trend.
struct WindowDrift {
  static constexpr int kCount = 8;
  // traction_force_N ... sinkage_m, vertical_pressure_force_N, rim_longitudinal_force_N
  static const std::array<const char*, kCount> names;
  std::array<double, kCount> second_less_first{};
};

// A force's mean over the window is a steady-state answer when its drift is
// within 5 % of the mean or 20 N, whichever is larger (the floor: a force near
// zero, where 5 % is below the noise of the exchange's force sum). A run whose
// window is not steady says which forces were not (results "unsteady_forces").
constexpr double kSteadyDriftShare = 0.05, kSteadyDriftFloor_N = 20.0;
bool steady_force(double mean_N, double drift_N);

struct WindowMeans {
  double window_s = 0.0;
  long count = 0;  // rows averaged
  double start_s = 0.0, end_s = 0.0;  // time of the first and last row averaged (count > 0)
  ForceDecomposition mean;  // of the fields the results report (not the F4 parts, not delta x)
  double rim_longitudinal_force_N = 0.0, contact_force_x_N = 0.0;
  bool has_drift = false;  // count >= 2
  WindowDrift drift;
};

// The means of the window's rows; all 0 with no row.
WindowMeans window_means(const ForceWindow& window);

// The results of the means (averaging_window_*, averaged_steps, each mean, window_drift)
// and the last row's contact area and sinkage (final_*).
void put_window_results(const ForceWindow& window, nlohmann::json& results);

}  // namespace coupler
