#pragma once
// The work of the motion resistance over the wheel's forward travel,
// W = integral F1 dx_rim (thesis 2.1.1 for F1): what the terrain's resistance
// took from the rolling wheel, to set beside the terrain's plastic work
// (docs/force_decomposition.md, "Where the work goes").
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/checkpoint.hpp"

namespace coupler {

// Summed exchange by exchange: the loads of an exchange are held on the tyre
// over the window that follows it (docs/coupling.md), while the rim moves from
// this exchange's rim_x to the next one's, so each window adds
// F1(exchange n) (x(n + 1) - x(n)): the work of the held force, exactly.
struct ResistanceWork {
  double work_J = 0.0;      // integral F1 dx
  double distance_m = 0.0;  // integral dx: the rim's forward travel
  bool started = false;
  double last_rim_x_m = 0.0, last_motion_resistance_N = 0.0, last_time_s = 0.0;
  // The start of the first window over which the rim moved (-1: it has not):
  // before it the wheel was loaded in place, and F1 did no work.
  double travel_start_s = -1.0;

  // One exchange: its time, the rim's position and this exchange's F1.
  void add(double time_s, double rim_x_m, double motion_resistance_N);
  // "<prefix>..." named values; restore reads what save wrote.
  void save(cosim::CheckpointWriter& out, const std::string& prefix) const;
  void restore(const cosim::CheckpointReader& in, const std::string& prefix);
  // motion_resistance_work_J, the distance it was done over and when the travel started.
  void put_results(nlohmann::json& results) const;
};

}  // namespace coupler
