// Stiff and extreme tyre cases (configs/scenes/stability/tyre_*): each runs its
// bounded number of steps with a finite state and reports its energy balance;
// a fixed time step above the stable limit is refused.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "cosim/error.hpp"
#include "tyre_support.hpp"

namespace {

// Abaqus's guidance for explicit runs: energy balance within ~1-5 % of the largest energy.
constexpr double kEnergyTolerance = 0.05;

std::string stability_scene(const std::string& name) {
  return tyre_support::source_dir() + "/configs/scenes/stability/" + name + ".textproto";
}

class TyreStability : public ::testing::TestWithParam<const char*> {};

TEST_P(TyreStability, RunsFiniteWithBoundedEnergyError) {
  const auto out = tyre_support::scratch(std::string("tyre_stability_") + GetParam());
  nlohmann::json s;
  ASSERT_NO_THROW(s = tyre_support::run(stability_scene(GetParam()), {}, out));  // NaN/Inf throws
  EXPECT_TRUE(s["status"] == "completed" || s["status"] == "stopped_at_max_steps") << s["status"];
  EXPECT_GT(s["steps"].get<long>(), 0);
  const double error = s["energy"]["relative_error"];
  std::printf("%s: %ld steps, dt %.3e s (%s), energy error %.2e\n", GetParam(), s["steps"].get<long>(),
              s["dt_s"].get<double>(), s["time_step"]["controlling_region"].get<std::string>().c_str(), error);
  EXPECT_TRUE(std::isfinite(s["energy"]["kinetic_J"].get<double>()));
  EXPECT_LT(error, kEnergyTolerance);
}

INSTANTIATE_TEST_SUITE_P(Scenes, TyreStability,
                         ::testing::Values("tyre_steel_time_step", "tyre_incompressible_rubber", "tyre_400kPa",
                                           "tyre_28ms", "tyre_800Nm"));

TEST(TyreStability, SteelSetsTheUnscaledTimeStep) {
  const auto s = tyre_support::run(stability_scene("tyre_steel_time_step"), {"time.max_steps=2"},
                                   tyre_support::scratch("tyre_steel_dt"));
  const std::string region = s["time_step"]["controlling_region"];
  EXPECT_EQ(region, "bead");  // the deformable solid steel bead
  EXPECT_LT(s["time_step"]["stable_dt_s"].get<double>(), 1e-6);
  EXPECT_EQ(s["time_step"]["added_mass_kg"].get<double>(), 0.0);
}

TEST(TyreStability, FixedTimeStepAboveTheLimitIsRefused) {
  try {
    tyre_support::run(stability_scene("tyre_400kPa"), {"time.fixed_dt_s=1e-4"}, tyre_support::scratch("tyre_refused"));
    FAIL() << "a time step of 1e-4 s was accepted";
  } catch (const cosim::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("fixed_dt_s"), std::string::npos) << what;
    EXPECT_NE(what.find("stable limit"), std::string::npos) << what;
  }
}

}  // namespace
