#pragma once
// Hydroplaning (thesis 4.2): a tyre rolls on a rigid road under a water layer
// while its forward speed ramps up; the water's lift takes the wheel load off
// the road until the tyre floats. The road's share of the wheel load against
// the speed is the curve every criterion is read from; the critical velocity
// is the speed from which that share stays below a stated fraction
// (docs/water.md says why 10 %).
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

namespace cosim {
class CheckpointWriter;
class CheckpointReader;
}  // namespace cosim

namespace tyre_fe {

// The road's share of the wheel load against the speed, per sample.
struct RoadShareCurve {
  std::vector<double> time_s, speed_m_per_s;
  std::vector<double> road_share;  // road force / wheel load, centred moving mean over filter_s
};

// time_s ascending; road_force_z_N the road's vertical force on the tyre.
// The raw road force swings with the particles entering and leaving the
// footprint; the centred moving mean over filter_s (cosim/signal.hpp) is the
// curve read. Throws cosim::Error if the series differ in length or the load is not positive.
RoadShareCurve road_share_curve(const std::vector<double>& time_s, const std::vector<double>& speed_m_per_s,
                                const std::vector<double>& road_force_z_N, double wheel_load_N, double filter_s);

// The speed at which the share falls below `share` for the last time (from
// there to the curve's end it stays below), linear between samples; the first
// speed if it is below from the start; NaN if it is not below at the end, or
// below for less than `held_s` before the end. A fall within the last moments
// of a reading (the curve's mean there is one-sided; the tyre reaches the end
// of its water) is not established; the run calls it with the mean's width.
double speed_below_road_share(const RoadShareCurve& curve, double share, double held_s = 0.0);

// Where the tyre's tread meets the water surface ahead of the rim [m]: the
// undeformed tread circle (radius_m) cut by the surface, the rim
// rim_height_m above it; 0 if the circle does not reach the surface.
double tread_lead_at_surface_m(double radius_m, double rim_height_m);

// How many of the first samples to read: those before the tread's leading
// edge at the water surface (rim x + lead_m) reaches the water's downstream
// end. After it the tyre runs out of water: the lift fades and the tyre lands
// on the bare road, which is not hydroplaning. The rim's positions are the
// speeds integrated back (trapezoid) from its position at the last sample.
std::size_t samples_over_water(const std::vector<double>& time_s, const std::vector<double>& speed_m_per_s,
                               double last_rim_x_m, double lead_m, double water_end_x_m);

// The criterion of the reported critical velocity: the road carries less than this share of the load.
inline constexpr double kHydroplaningRoadShare = 0.10;
// The smoothing of the road force [s]: a tyre at 10 m/s passes 5 cm of road in it.
inline constexpr double kHydroplaningFilter_s = 0.005;
// Afloat (tyre.stages.end_rolling_when_afloat): below the criterion's share,
// trailing 5 ms mean, for this long [s]: six times the filter, about two
// footprint lengths of road at 14 m/s.
inline constexpr double kAfloatHold_s = 0.03;

// The rolling stage's record of a tyre on a road under water: every step the
// rim's forward speed, the road's vertical force on the tyre and the water's.
// It also watches whether the tyre is afloat, from the samples so far.
class HydroplaningSamples {
 public:
  void add(double time_s, double speed_m_per_s, double road_force_z_N, double water_lift_z_N);
  // After add: the road has carried less than kHydroplaningRoadShare of the
  // load, as a trailing kHydroplaningFilter_s mean (the centred mean of the
  // reading needs samples not yet taken), for kAfloatHold_s. Asked after every
  // add (it keeps when the share last stood at the criterion); asking twice
  // for one sample gives the same answer.
  bool afloat(double wheel_load_N);
  std::size_t size() const { return time_s_.size(); }
  const std::vector<double>& time_s() const { return time_s_; }
  const std::vector<double>& speed_m_per_s() const { return speed_; }
  const std::vector<double>& road_force_z_N() const { return road_; }
  const std::vector<double>& water_lift_z_N() const { return lift_; }
  // A checkpoint's records "hydroplaning.*"; restore throws cosim::Error naming the file.
  void save(cosim::CheckpointWriter& out) const;
  void restore(const cosim::CheckpointReader& in);

 private:
  std::vector<double> time_s_, speed_, road_, lift_;
  // The trailing mean's first sample and sum; since when it has been below the criterion.
  std::size_t trail_begin_ = 0;
  double trail_sum_ = 0.0, below_since_ = 0.0;
};

// What a run reads from its samples: those taken before the tread's leading
// edge reached the water's end (samples_over_water), as the road's share
// curve and the water's lift (both kHydroplaningFilter_s centred means).
struct HydroplaningReading {
  std::size_t samples_over_water = 0;  // fewer than 2: nothing to read
  RoadShareCurve curve;
  std::vector<double> water_lift_N;
  nlohmann::json results;  // the run's results.hydroplaning
};
// water_end_x_m infinite: water to the end of the run.
HydroplaningReading read_hydroplaning(const HydroplaningSamples& samples, double wheel_load_N, double last_rim_x_m,
                                      double tread_lead_m, double water_end_x_m, bool ended_afloat);

}  // namespace tyre_fe
