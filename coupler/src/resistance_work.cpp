// The work of the motion resistance; see resistance_work.hpp.
#include "coupler/resistance_work.hpp"

namespace coupler {

void ResistanceWork::add(double time_s, double rim_x_m, double motion_resistance_N) {
  if (started) {
    const double dx = rim_x_m - last_rim_x_m;
    work_J += last_motion_resistance_N * dx;
    distance_m += dx;
    if (dx != 0.0 && travel_start_s < 0.0) travel_start_s = last_time_s;
  }
  started = true;
  last_rim_x_m = rim_x_m, last_motion_resistance_N = motion_resistance_N, last_time_s = time_s;
}

void ResistanceWork::save(cosim::CheckpointWriter& out, const std::string& prefix) const {
  out.put_value(prefix + "motion_resistance_work_J", work_J);
  out.put_value(prefix + "motion_resistance_distance_m", distance_m);
  out.put_value<double>(prefix + "motion_resistance_started", started ? 1.0 : 0.0);
  out.put_value(prefix + "last_rim_x_m", last_rim_x_m);
  out.put_value(prefix + "last_motion_resistance_N", last_motion_resistance_N);
  out.put_value(prefix + "last_time_s", last_time_s);
  out.put_value(prefix + "travel_start_s", travel_start_s);
}

void ResistanceWork::restore(const cosim::CheckpointReader& in, const std::string& prefix) {
  work_J = in.get_value<double>(prefix + "motion_resistance_work_J");
  distance_m = in.get_value<double>(prefix + "motion_resistance_distance_m");
  started = in.get_value<double>(prefix + "motion_resistance_started") != 0.0;
  last_rim_x_m = in.get_value<double>(prefix + "last_rim_x_m");
  last_motion_resistance_N = in.get_value<double>(prefix + "last_motion_resistance_N");
  last_time_s = in.get_value<double>(prefix + "last_time_s");
  travel_start_s = in.get_value<double>(prefix + "travel_start_s");
}

void ResistanceWork::put_results(nlohmann::json& results) const {
  results["motion_resistance_work_J"] = work_J;
  results["motion_resistance_distance_m"] = distance_m;
  if (travel_start_s >= 0.0) results["rim_travel_start_s"] = travel_start_s;
}

}  // namespace coupler
