// The steady means of a coupled run (coupler/force_window.hpp): the rows of the
// last averaging window, their means and drift, and the rows through a checkpoint.
// The means are compared exactly: the rows hold small integers and dyadic
// times, so every sum and quotient below is exact in double precision; and a
// mean is also checked to the bit against the sum in row order divided once by
// the count, the order the recorded runs' results depend on.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cosim/checkpoint.hpp"
#include "cosim/error.hpp"
#include "coupler/force_window.hpp"
#include "test_paths.hpp"

namespace {

coupler::ForceRow row(double t, double f) {
  coupler::ForceRow r;
  r.time_s = t;
  r.d.traction_force_N = f, r.d.motion_resistance_N = 2 * f, r.d.groove_force_N = -f;
  r.d.rolling_resistance_force_N = 3 * f, r.d.drawbar_pull_N = f + 1, r.d.sinkage_m = 0.5 * f;
  r.d.contact_area_m2 = 0.25 * f, r.d.pressure_centre_offset_m = 0.125 * f;
  r.rim_longitudinal_force_N = 10 * f, r.contact_force_x_N = -10 * f;
  return r;
}

// Rows at t = 0, 0.5, ..., 2 with traction 1, 2, 3, 4, 6.
coupler::ForceWindow five_rows(double window_s) {
  coupler::ForceWindow w(window_s);
  const double f[5] = {1, 2, 3, 4, 6};
  for (int i = 0; i < 5; ++i) w.add(row(0.5 * i, f[i]));
  return w;
}

}  // namespace

TEST(CouplerWindowMeans, KeepsTheRowsOfTheLastWindowOnly) {
  const coupler::ForceWindow w = five_rows(1.0);
  ASSERT_EQ(w.rows().size(), 3u);  // t >= 2 - 1: the row at the window's start is in it
  EXPECT_EQ(w.rows().front().time_s, 1.0);
  EXPECT_EQ(five_rows(0.0).rows().size(), 5u);  // no window: every row
}

TEST(CouplerWindowMeans, MeansAreTheRowSumsOverTheCount) {
  const coupler::WindowMeans m = coupler::window_means(five_rows(1.0));  // the rows of 3, 4, 6
  EXPECT_EQ(m.count, 3);
  EXPECT_EQ(m.window_s, 1.0);
  EXPECT_EQ(m.start_s, 1.0);
  EXPECT_EQ(m.end_s, 2.0);
  EXPECT_EQ(m.mean.traction_force_N, 13.0 / 3);  // the order of the sum and one division, to the bit
  EXPECT_EQ(m.mean.motion_resistance_N, 26.0 / 3);
  EXPECT_EQ(m.mean.rolling_resistance_force_N, 13.0);
  EXPECT_EQ(m.mean.drawbar_pull_N, 16.0 / 3);
  EXPECT_EQ(m.mean.sinkage_m, 6.5 / 3);
  EXPECT_EQ(m.mean.contact_area_m2, 3.25 / 3);
  EXPECT_EQ(m.rim_longitudinal_force_N, 130.0 / 3);
  EXPECT_EQ(m.contact_force_x_N, -130.0 / 3);
  EXPECT_EQ(m.mean.pressure_centre_offset_m, 0.0);  // not a reported mean
  const coupler::WindowMeans all = coupler::window_means(five_rows(0.0));
  EXPECT_EQ(all.count, 5);
  EXPECT_EQ(all.start_s, 0.0);
  EXPECT_EQ(all.mean.traction_force_N, 16.0 / 5);
}

TEST(CouplerWindowMeans, DriftIsTheSecondHalfsMeanLessTheFirsts) {
  // Window [1, 2], middle 1.5: first half the row of 3, second those of 4 and 6.
  const coupler::WindowMeans m = coupler::window_means(five_rows(1.0));
  ASSERT_TRUE(m.has_drift);
  EXPECT_EQ(std::string(coupler::WindowDrift::names[0]), "traction_force_N");
  EXPECT_EQ(m.drift.second_less_first[0], 5.0 - 3.0);
  EXPECT_EQ(m.drift.second_less_first[1], 10.0 - 6.0);          // motion resistance
  EXPECT_EQ(m.drift.second_less_first[5], 2.5 - 1.5);           // sinkage
  // No window: the halves of the whole run, middle 1: rows 1, 2 against 3, 4, 6.
  EXPECT_EQ(coupler::window_means(five_rows(0.0)).drift.second_less_first[0], 13.0 / 3 - 1.5);
}

TEST(CouplerWindowMeans, ResultsOfAWindowAndOfNoRow) {
  nlohmann::json results;
  coupler::put_window_results(five_rows(1.0), results);
  EXPECT_EQ(results["averaged_steps"], 3);
  EXPECT_EQ(results["averaging_window_start_s"], 1.0);
  EXPECT_EQ(results["averaging_window_end_s"], 2.0);
  EXPECT_EQ(results["traction_force_N"], 13.0 / 3);
  EXPECT_EQ(results["terrain_longitudinal_force_N"], -130.0 / 3);
  EXPECT_EQ(results["window_drift"]["traction_force_N"], 2.0);
  EXPECT_EQ(results["final_contact_area_m2"], 1.5);
  EXPECT_EQ(results["final_sinkage_m"], 3.0);
  nlohmann::json none;
  coupler::put_window_results(coupler::ForceWindow(1.0), none);
  EXPECT_EQ(none["averaged_steps"], 0);
  EXPECT_EQ(none["traction_force_N"], 0.0);
  EXPECT_FALSE(none.contains("averaging_window_start_s"));
  EXPECT_FALSE(none.contains("window_drift"));
  EXPECT_FALSE(none.contains("final_sinkage_m"));
}

// The acceptance rule of a steady window: drift within 5 % of the mean or 20 N,
// whichever is larger; on both sides of each bound.
TEST(CouplerWindowMeans, AForceIsSteadyWhenItsDriftIsWithinFivePercentOrTwentyNewtons) {
  EXPECT_TRUE(coupler::steady_force(1000.0, 50.0));  // 5 % of 1000 N
  EXPECT_FALSE(coupler::steady_force(1000.0, 50.5));
  EXPECT_TRUE(coupler::steady_force(-1000.0, -49.0));  // the size of the mean, either sign
  EXPECT_TRUE(coupler::steady_force(100.0, 20.0));     // the 20 N floor above 5 % of 100 N
  EXPECT_FALSE(coupler::steady_force(100.0, -20.5));
  EXPECT_TRUE(coupler::steady_force(0.0, 0.0));
}

// five_rows(1.0): traction 13/3 N drifts by 2 N (steady by the floor); with the
// forces scaled by 100 the traction (433 N) drifts by 200 N and every force
// with it, and the run names them; the sinkage is never judged.
TEST(CouplerWindowMeans, TheResultsNameTheForcesWhoseWindowIsNotSteady) {
  nlohmann::json small;
  coupler::put_window_results(five_rows(1.0), small);
  EXPECT_TRUE(small["window_steady"].get<bool>());
  EXPECT_TRUE(small["unsteady_forces"].empty());
  coupler::ForceWindow large(1.0);
  const double f[5] = {1, 2, 3, 4, 6};
  for (int i = 0; i < 5; ++i) large.add(row(0.5 * i, 100 * f[i]));
  nlohmann::json results;
  coupler::put_window_results(large, results);
  EXPECT_FALSE(results["window_steady"].get<bool>());
  const auto& unsteady = results["unsteady_forces"];
  EXPECT_NE(std::find(unsteady.begin(), unsteady.end(), "traction_force_N"), unsteady.end());
  EXPECT_NE(std::find(unsteady.begin(), unsteady.end(), "rim_longitudinal_force_N"), unsteady.end());
  EXPECT_EQ(std::find(unsteady.begin(), unsteady.end(), "sinkage_m"), unsteady.end());
}

TEST(CouplerWindowMeans, RowsGoThroughACheckpointAsNamedColumns) {
  const std::string path = test_support::scratch("coupler_window_means") + "/window.ckpt";
  const coupler::ForceWindow saved = five_rows(1.0);
  cosim::CheckpointWriter out("coupler", 7, 12, 2.0);
  saved.save(out, "coupler.window.");
  out.commit(path);
  const cosim::CheckpointReader in(path);
  EXPECT_EQ(in.get<double>("coupler.window.traction_force_N"), (std::vector<double>{3, 4, 6}));
  EXPECT_EQ(in.get<double>("coupler.window.time_s"), (std::vector<double>{1.0, 1.5, 2.0}));
  coupler::ForceWindow restored(1.0);
  restored.restore(in, "coupler.window.");
  ASSERT_EQ(restored.rows().size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {  // bits copied, so equal
    const coupler::ForceRow &a = saved.rows()[i], &b = restored.rows()[i];
    EXPECT_EQ(a.time_s, b.time_s);
    EXPECT_EQ(a.d.traction_force_N, b.d.traction_force_N);
    EXPECT_EQ(a.d.pressure_centre_offset_m, b.d.pressure_centre_offset_m);
    EXPECT_EQ(a.d.contact_area_m2, b.d.contact_area_m2);
    EXPECT_EQ(a.contact_force_x_N, b.contact_force_x_N);
  }
  EXPECT_THROW(restored.restore(in, "coupler.other."), cosim::Error);
}
