#include "tyre_fe/hydroplaning.hpp"

#include <cmath>
#include <limits>

#include "cosim/error.hpp"
#include "cosim/signal.hpp"

namespace tyre_fe {

RoadShareCurve road_share_curve(const std::vector<double>& time_s, const std::vector<double>& speed_m_per_s,
                                const std::vector<double>& road_force_z_N, double wheel_load_N, double filter_s) {
  if (time_s.size() != speed_m_per_s.size() || time_s.size() != road_force_z_N.size())
    throw cosim::Error("road share curve: " + std::to_string(time_s.size()) + " times, " +
                       std::to_string(speed_m_per_s.size()) + " speeds and " + std::to_string(road_force_z_N.size()) +
                       " road forces");
  if (!(wheel_load_N > 0.0))
    throw cosim::Error("road share curve: the wheel load must be positive, not " + cosim::number_text(wheel_load_N));
  RoadShareCurve c;
  c.time_s = time_s;
  c.speed_m_per_s = speed_m_per_s;
  c.road_share = cosim::centred_moving_mean(time_s, road_force_z_N, filter_s);
  for (double& s : c.road_share) s /= wheel_load_N;
  return c;
}

double speed_below_road_share(const RoadShareCurve& c, double share, double held_s) {
  const auto& y = c.road_share;
  const auto& v = c.speed_m_per_s;
  const double none = std::numeric_limits<double>::quiet_NaN();
  if (y.empty() || !(y.back() < share)) return none;
  std::size_t i = y.size() - 1;
  while (i > 0 && y[i - 1] < share) --i;  // the first sample of the last run below
  if (c.time_s.back() - c.time_s[i] < held_s) return none;
  if (i == 0) return v.front();
  // Crossing between samples i - 1 (at or above) and i (below).
  const double f = (y[i - 1] - share) / (y[i - 1] - y[i]);
  return v[i - 1] + f * (v[i] - v[i - 1]);
}

double tread_lead_at_surface_m(double radius_m, double rim_height_m) {
  return std::fabs(rim_height_m) < radius_m ? std::sqrt(radius_m * radius_m - rim_height_m * rim_height_m) : 0.0;
}

std::size_t samples_over_water(const std::vector<double>& t, const std::vector<double>& v, double last_rim_x_m,
                               double lead_m, double water_end_x_m) {
  if (t.size() != v.size())
    throw cosim::Error("samples over water: " + std::to_string(t.size()) + " times and " + std::to_string(v.size()) +
                       " speeds");
  if (t.empty()) return 0;
  std::vector<double> x(t.size());
  x.back() = last_rim_x_m;
  for (std::size_t i = t.size() - 1; i > 0; --i) x[i - 1] = x[i] - 0.5 * (v[i] + v[i - 1]) * (t[i] - t[i - 1]);
  std::size_t n = 0;
  while (n < x.size() && x[n] + lead_m < water_end_x_m) ++n;
  return n;
}

}  // namespace tyre_fe
