// Stiff and extreme cases (configs/scenes/stability/): each runs its bounded
// number of steps with a finite state and a bounded energy balance error.
#include <gtest/gtest.h>

#include "cosim/error.hpp"
#include "test_support.hpp"

namespace {

// Abaqus's guidance for explicit runs is an energy balance within ~1-5 % of
// the largest energy; we hold the stiff cases to 5 %.
constexpr double kEnergyTolerance = 0.05;

class Stability : public ::testing::TestWithParam<const char*> {};

TEST_P(Stability, RunsFiniteWithBoundedEnergyError) {
  const std::string scene = test_support::source_dir() + "/configs/scenes/stability/" + GetParam() + ".textproto";
  const auto out = test_support::scratch(std::string("stability_") + GetParam());
  nlohmann::json s;
  ASSERT_NO_THROW(s = test_support::run(scene, {}, out));  // a NaN/Inf throws
  EXPECT_EQ(s["status"], "completed");
  EXPECT_GT(s["steps"].get<long>(), 0);
  const double error = s["energy"]["relative_error"];
  std::printf("%s: %ld steps, energy error %.2e\n", GetParam(), s["steps"].get<long>(), error);
  EXPECT_LT(error, kEnergyTolerance);
  EXPECT_TRUE(std::isfinite(s["energy"]["kinetic_J"].get<double>()));
}

TEST_P(Stability, FixedTimeStepAboveLimitIsRefused) {
  const std::string scene = test_support::source_dir() + "/configs/scenes/stability/" + GetParam() + ".textproto";
  EXPECT_THROW(test_support::run(scene, {"time.fixed_dt_s=0.01"}, test_support::scratch("refused")), cosim::Error);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Stability,
                         ::testing::Values("water_full_sound_speed", "hard_snow_plate",
                                           "plate_impact_28ms", "fine_spacing"));
}  // namespace
