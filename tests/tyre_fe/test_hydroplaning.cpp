// The critical velocity read from a road-force curve (tyre_fe/hydroplaning.hpp):
// a synthetic ramp whose crossing speeds are known in closed form, with the
// per-step noise of a coupled run on top.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "cosim/checkpoint.hpp"
#include "cosim/error.hpp"
#include "tyre_fe/hydroplaning.hpp"

namespace {

// Speed ramped linearly 0 -> 28 m/s over 0.4 s in 6 us steps (the scene's ramp
// and its coupling window); road force L (1 - (v / vc)^2), floored at 0 (the lift
// of a planing surface grows as v^2), with +-300 N alternating from step to step
// (the swing of particles entering and leaving the footprint).
struct Ramp {
  std::vector<double> t, v, road;
};
Ramp make_ramp(double load, double vc, double noise_N) {
  Ramp r;
  const double dt = 6e-6, end = 0.4, top = 28.0;
  for (int i = 0; i * dt <= end; ++i) {
    const double t = i * dt, v = top * t / end;
    r.t.push_back(t), r.v.push_back(v);
    r.road.push_back(std::max(0.0, load * (1.0 - v * v / (vc * vc))) + (i % 2 ? noise_N : -noise_N));
  }
  return r;
}

// The centred 5 ms mean of a curve quadratic in time moves the crossing by
// a^2 w^2 / (24 v) (a = 70 m/s^2, w = 5 ms: 5e-4 m/s at 10 m/s); the noise's
// residual after the mean (one unpaired sample of 833) by another 7e-4 m/s.
// 0.01 m/s is ten times their sum, and a hundredth of what sets the thesis's
// treads apart (11.5, 14.0, 27.3 m/s).
constexpr double kTolerance = 0.01;

TEST(Hydroplaning, TheSpeedsWhereTheRoadShareFallsBelowAFractionAreTheClosedForms) {
  const double load = 4000.0, vc = 15.0;
  const Ramp r = make_ramp(load, vc, 300.0);
  const auto curve = tyre_fe::road_share_curve(r.t, r.v, r.road, load, tyre_fe::kHydroplaningFilter_s);
  for (double share : {0.5, 0.25, 0.1})
    EXPECT_NEAR(tyre_fe::speed_below_road_share(curve, share), vc * std::sqrt(1.0 - share), kTolerance)
        << "share " << share;
}

TEST(Hydroplaning, ADipThatRecoversIsNotTheCriticalVelocity) {
  const double load = 4000.0, vc = 20.0;
  Ramp r = make_ramp(load, vc, 0.0);
  // 20 ms with the road force at 0 around 5 m/s (t = 0.07 s): the road carries the load again after it.
  for (std::size_t i = 0; i < r.t.size(); ++i)
    if (r.t[i] > 0.06 && r.t[i] < 0.08) r.road[i] = 0.0;
  const auto curve = tyre_fe::road_share_curve(r.t, r.v, r.road, load, tyre_fe::kHydroplaningFilter_s);
  EXPECT_NEAR(tyre_fe::speed_below_road_share(curve, 0.1), vc * std::sqrt(0.9), kTolerance);
}

TEST(Hydroplaning, ACriterionNotReachedByTheTopSpeedIsNaN) {
  const double load = 4000.0, vc = 40.0;  // at 28 m/s the road still carries 51 %
  const Ramp r = make_ramp(load, vc, 300.0);
  const auto curve = tyre_fe::road_share_curve(r.t, r.v, r.road, load, tyre_fe::kHydroplaningFilter_s);
  EXPECT_TRUE(std::isnan(tyre_fe::speed_below_road_share(curve, 0.1)));
  EXPECT_NEAR(tyre_fe::speed_below_road_share(curve, 0.6), vc * std::sqrt(0.4), kTolerance);
}

// A fall below the fraction in the last 2 ms of a reading (within the 5 ms
// mean's half-width of its end) is not a critical velocity; one 10 ms before
// the end is. The ramp cut where its share falls below 10 % plus 2 ms / 10 ms.
TEST(Hydroplaning, AFallInTheReadingsLastMomentsIsNotEstablished) {
  const double load = 4000.0, vc = 15.0;
  const Ramp r = make_ramp(load, vc, 0.0);
  const double t_cross = vc * std::sqrt(0.9) * 0.4 / 28.0;  // v = 28 t / 0.4
  for (const double after_s : {0.002, 0.010}) {
    Ramp cut;
    for (std::size_t i = 0; i < r.t.size() && r.t[i] <= t_cross + after_s; ++i)
      cut.t.push_back(r.t[i]), cut.v.push_back(r.v[i]), cut.road.push_back(r.road[i]);
    const auto curve = tyre_fe::road_share_curve(cut.t, cut.v, cut.road, load, tyre_fe::kHydroplaningFilter_s);
    const double v = tyre_fe::speed_below_road_share(curve, 0.1, tyre_fe::kHydroplaningFilter_s);
    if (after_s < tyre_fe::kHydroplaningFilter_s) EXPECT_TRUE(std::isnan(v)) << v;
    // The one-sided mean at the cut's end moves the crossing by ~1e-3 m/s (a quadratic over 2.5 ms).
    else EXPECT_NEAR(v, vc * std::sqrt(0.9), kTolerance);
  }
}

// The tread circle of radius 5 cut by a surface 3 below the centre: 4 ahead (3-4-5).
TEST(Hydroplaning, TheTreadMeetsTheSurfaceWhereTheCircleCutsIt) {
  EXPECT_DOUBLE_EQ(tyre_fe::tread_lead_at_surface_m(0.5, 0.3), 0.4);
  EXPECT_EQ(tyre_fe::tread_lead_at_surface_m(0.3, 0.5), 0.0);  // the tyre above the water
}

// The scene's ramp: x(t) = 28 t^2 / (2 0.4) from x = 0 at t = 0 (the speed is
// linear, so the trapezoid integrates it exactly; round-off ~1e-15 m). With the
// rim's last position given, the samples read are those with x + lead below the
// water's end: t < sqrt((end - lead) 2 0.4 / 28).
TEST(Hydroplaning, TheReadingEndsWhereTheTreadReachesTheEndOfTheWater) {
  const Ramp r = make_ramp(4000.0, 15.0, 0.0);
  const double top = 28.0, ramp = 0.4, lead = 0.17, end = 2.3;
  const double last_x = top * r.t.back() * r.t.back() / (2 * ramp);
  const std::size_t n = tyre_fe::samples_over_water(r.t, r.v, last_x, lead, end);
  const double t_end = std::sqrt((end - lead) * 2 * ramp / top);
  ASSERT_GT(n, 0u);
  ASSERT_LT(n, r.t.size());
  EXPECT_LT(r.t[n - 1], t_end);
  EXPECT_GE(r.t[n], t_end);
  EXPECT_EQ(tyre_fe::samples_over_water(r.t, r.v, last_x, lead, 10.0), r.t.size());  // never reaches the end
}

// The afloat watch (tyre.stages.end_rolling_when_afloat) on a road force that
// drops from the load to 0 at t0, sampled every 6 us: the trailing 5 ms mean
// falls below 10 % once 90 % of its window is past t0 (t0 + 4.5 ms), and the
// tyre is afloat kAfloatHold_s after that: t0 + 34.5 ms. The window's edge
// and the hold's test each land on a sample, so the tolerance is 3 samples.
struct Drop {
  std::vector<double> t, road;
};
Drop make_drop(double load, double t0, double end) {
  Drop d;
  for (int i = 0; i * 6e-6 <= end; ++i) d.t.push_back(i * 6e-6), d.road.push_back(i * 6e-6 < t0 ? load : 0.0);
  return d;
}
double first_afloat(tyre_fe::HydroplaningSamples& samples, const Drop& d, std::size_t from, double load) {
  for (std::size_t i = from; i < d.t.size(); ++i) {
    samples.add(d.t[i], 10.0, d.road[i], load - d.road[i]);
    if (samples.afloat(load)) return d.t[i];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

TEST(Hydroplaning, TheTyreIsAfloatWhenTheTrailingMeanHasStayedBelowTheCriterionForTheHold) {
  const double load = 4000.0, t0 = 0.1;
  const Drop d = make_drop(load, t0, 0.2);
  tyre_fe::HydroplaningSamples samples;
  const double expected = t0 + (1.0 - tyre_fe::kHydroplaningRoadShare) * tyre_fe::kHydroplaningFilter_s +
                          tyre_fe::kAfloatHold_s;
  EXPECT_NEAR(first_afloat(samples, d, 0, load), expected, 3 * 6e-6);
}

TEST(Hydroplaning, ADipShorterThanTheHoldIsNotAfloat) {
  const double load = 4000.0;
  Drop d = make_drop(load, 0.1, 0.2);
  for (std::size_t i = 0; i < d.t.size(); ++i) d.road[i] = d.t[i] > 0.1 && d.t[i] < 0.12 ? 0.0 : load;
  tyre_fe::HydroplaningSamples samples;
  EXPECT_TRUE(std::isnan(first_afloat(samples, d, 0, load)));
}

// A run restarted from a checkpoint taken while the road force is below the
// criterion but not yet for the hold must find the tyre afloat at the same
// sample as the run that went on: the watch's trailing state is in the checkpoint.
TEST(Hydroplaning, TheAfloatWatchContinuesFromACheckpoint) {
  const double load = 4000.0, t0 = 0.1;
  const Drop d = make_drop(load, t0, 0.2);
  tyre_fe::HydroplaningSamples straight, before;
  const double afloat_at = first_afloat(straight, d, 0, load);
  std::size_t cut = 0;
  while (d.t[cut] < t0 + 0.02) before.add(d.t[cut], 10.0, d.road[cut], load - d.road[cut]), before.afloat(load), ++cut;
  const std::string path = ::testing::TempDir() + "hydroplaning_watch.ckpt";
  cosim::CheckpointWriter out("tyre_fe", 1, cut, d.t[cut - 1]);
  before.save(out);
  out.commit(path);
  tyre_fe::HydroplaningSamples restored;
  restored.restore(cosim::CheckpointReader(path));
  std::remove(path.c_str());
  EXPECT_EQ(restored.size(), cut);
  EXPECT_EQ(first_afloat(restored, d, cut, load), afloat_at);
}

// The run's reading over a ramp whose crossing is known in closed form
// (vc sqrt(0.9), as above), with water to the end and with the water ending
// before the crossing: then no critical velocity, and the speed where the tread
// reached the end is the first sample not read.
TEST(Hydroplaning, TheReadingStopsAtTheWatersEnd) {
  const double load = 4000.0, vc = 15.0, top = 28.0, ramp = 0.4, lead = 0.17;
  const Ramp r = make_ramp(load, vc, 300.0);
  tyre_fe::HydroplaningSamples samples;
  for (std::size_t i = 0; i < r.t.size(); ++i) samples.add(r.t[i], r.v[i], r.road[i], load - r.road[i]);
  const double last_x = top * r.t.back() * r.t.back() / (2 * ramp);
  const double no_end = std::numeric_limits<double>::infinity();
  const auto all = tyre_fe::read_hydroplaning(samples, load, last_x, lead, no_end, false);
  ASSERT_EQ(all.samples_over_water, r.t.size());
  EXPECT_NEAR(all.results["critical_velocity_m_per_s"].get<double>(), vc * std::sqrt(0.9), kTolerance);
  EXPECT_TRUE(all.results["water_end_x_m"].is_null());
  // The water ends where the rim is at 10 m/s: x = 10^2 ramp / (2 top).
  const double end = 100.0 * ramp / (2 * top) + lead;
  const auto cut = tyre_fe::read_hydroplaning(samples, load, last_x, lead, end, false);
  EXPECT_TRUE(cut.results["critical_velocity_m_per_s"].is_null());
  EXPECT_NEAR(cut.results["reached_the_end_of_the_water_at_speed_m_per_s"].get<double>(), 10.0, 28.0 * 6e-6 / 0.4);
  EXPECT_EQ(cut.water_lift_N.size(), cut.samples_over_water);
}

TEST(Hydroplaning, MismatchedSeriesAndABadLoadAreRefused) {
  EXPECT_THROW(tyre_fe::samples_over_water({0, 1}, {0}, 0, 0, 1), cosim::Error);
  EXPECT_THROW(tyre_fe::road_share_curve({0, 1}, {0}, {1, 1}, 4000, 0.005), cosim::Error);
  EXPECT_THROW(tyre_fe::road_share_curve({0, 1}, {0, 1}, {1, 1}, 0, 0.005), cosim::Error);
}

}  // namespace
