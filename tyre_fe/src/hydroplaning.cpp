#include "tyre_fe/hydroplaning.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "cosim/checkpoint.hpp"
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

void HydroplaningSamples::add(double time_s, double speed_m_per_s, double road_force_z_N, double water_lift_z_N) {
  time_s_.push_back(time_s), speed_.push_back(speed_m_per_s);
  road_.push_back(road_force_z_N), lift_.push_back(water_lift_z_N);
  // The trailing mean's window moves with every sample, whether or not afloat() is asked.
  trail_sum_ += road_force_z_N;
  while (time_s_[trail_begin_] < time_s - kHydroplaningFilter_s) trail_sum_ -= road_[trail_begin_++];
}

bool HydroplaningSamples::afloat(double wheel_load_N) {
  if (time_s_.empty()) return false;
  const double now = time_s_.back();
  const double share = trail_sum_ / double(time_s_.size() - trail_begin_) / wheel_load_N;
  if (share >= kHydroplaningRoadShare || time_s_.size() == 1) below_since_ = now;
  return now - below_since_ >= kAfloatHold_s;
}

void HydroplaningSamples::save(cosim::CheckpointWriter& out) const {
  out.put("hydroplaning.time_s", time_s_);
  out.put("hydroplaning.speed_m_per_s", speed_);
  out.put("hydroplaning.road_force_z_N", road_);
  out.put("hydroplaning.water_lift_z_N", lift_);
  out.put("hydroplaning.trail", std::vector<double>{trail_sum_, below_since_});
  out.put_value("hydroplaning.trail_begin", std::uint64_t(trail_begin_));
}

void HydroplaningSamples::restore(const cosim::CheckpointReader& in) {
  time_s_ = in.get<double>("hydroplaning.time_s");
  speed_ = in.get<double>("hydroplaning.speed_m_per_s", time_s_.size());
  road_ = in.get<double>("hydroplaning.road_force_z_N", time_s_.size());
  lift_ = in.get<double>("hydroplaning.water_lift_z_N", time_s_.size());
  const auto trail = in.get<double>("hydroplaning.trail", 2);
  trail_sum_ = trail[0], below_since_ = trail[1];
  trail_begin_ = in.get_value<std::uint64_t>("hydroplaning.trail_begin");
  if (trail_begin_ > time_s_.size())
    throw cosim::Error(in.path() + ": hydroplaning.trail_begin " + std::to_string(trail_begin_) + " beyond its " +
                       std::to_string(time_s_.size()) + " samples");
}

HydroplaningReading read_hydroplaning(const HydroplaningSamples& samples, double wheel_load_N, double last_rim_x_m,
                                      double tread_lead_m, double water_end_x_m, bool ended_afloat) {
  HydroplaningReading r;
  const std::size_t n =
      samples_over_water(samples.time_s(), samples.speed_m_per_s(), last_rim_x_m, tread_lead_m, water_end_x_m);
  r.samples_over_water = n;
  if (n < 2) return r;
  auto first_n = [n](const std::vector<double>& v) { return std::vector<double>(v.begin(), v.begin() + long(n)); };
  const std::vector<double> times = first_n(samples.time_s());
  r.curve = road_share_curve(times, first_n(samples.speed_m_per_s()), first_n(samples.road_force_z_N()), wheel_load_N,
                             kHydroplaningFilter_s);
  r.water_lift_N = cosim::centred_moving_mean(times, first_n(samples.water_lift_z_N()), kHydroplaningFilter_s);
  double least = 1e30;
  for (double share : r.curve.road_share) least = std::min(least, share);
  auto speed = [&](double share) {
    const double v = speed_below_road_share(r.curve, share, kHydroplaningFilter_s);
    return std::isnan(v) ? nlohmann::json() : nlohmann::json(v);
  };
  auto finite_or_null = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
  r.results = {
      {"critical_velocity_m_per_s", speed(kHydroplaningRoadShare)},
      {"criterion", "the road carries less than " + cosim::number_text(100 * kHydroplaningRoadShare) +
                        " % of the wheel load from this speed on (" + cosim::number_text(1e3 * kHydroplaningFilter_s) +
                        " ms centred mean); null: not reached"},
      {"speed_below_road_share_m_per_s",
       {{"50_percent", speed(0.5)}, {"25_percent", speed(0.25)}, {"10_percent", speed(0.1)}}},
      {"least_road_share", least},
      {"ended_afloat", ended_afloat},
      {"top_speed_m_per_s", r.curve.speed_m_per_s.back()},
      {"water_end_x_m", finite_or_null(water_end_x_m)},
      {"tread_lead_at_surface_m", tread_lead_m},
      {"reached_the_end_of_the_water_at_speed_m_per_s",
       n < samples.size() ? nlohmann::json(samples.speed_m_per_s()[n]) : nlohmann::json()}};
  return r;
}

}  // namespace tyre_fe
