// The coupling window of a coupled run (coupler/coupling_scheme.hpp) from the
// stable steps the peers propose: the terrain's step with the tyre sub-cycling
// (multi-rate), or the smaller of the two for both (the common-step reference).
// Exact comparisons: the window is one of the proposed steps (a copy or
// std::min) and the sub-steps an integer.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "cosim/error.hpp"
#include "coupler/coupling_scheme.hpp"

namespace sc = cosim::scene;

TEST(CouplerCouplingWindow, MultiRateTakesTheTerrainsStepAndTheTyreSubCycles) {
  const coupler::CouplingWindow w = coupler::choose_coupling_window(2.5e-6, 2.0e-5, sc::MULTIRATE);
  EXPECT_FALSE(w.common_step);
  EXPECT_EQ(w.window_s, 2.0e-5);
  EXPECT_EQ(w.tyre_substeps, 8);  // 2e-5 / 2.5e-6, an exact multiple: not 9
  EXPECT_EQ(w.tyre_proposed_dt_s, 2.5e-6);
  EXPECT_EQ(w.terrain_proposed_dt_s, 2.0e-5);
  EXPECT_EQ(coupler::choose_coupling_window(3e-6, 2e-5, sc::MULTIRATE).tyre_substeps, 7);  // ceil(6.67)
  // The scheme left unset is multi-rate (configs/schema/scene.proto).
  EXPECT_EQ(coupler::choose_coupling_window(3e-6, 2e-5, sc::SCHEME_UNSET).window_s, 2e-5);
  EXPECT_EQ(std::string(coupler::coupling_window_reason(w)), "multi-rate: the terrain's step, the tyre sub-cycles");
}

TEST(CouplerCouplingWindow, CommonStepTakesTheSmallerStepForBoth) {
  coupler::CouplingWindow w = coupler::choose_coupling_window(2.5e-6, 2.0e-5, sc::COMMON_STEP);
  EXPECT_TRUE(w.common_step);
  EXPECT_EQ(w.window_s, 2.5e-6);
  EXPECT_EQ(w.tyre_substeps, 1);
  w = coupler::choose_coupling_window(4e-5, 2.0e-5, sc::COMMON_STEP);  // a terrain slower than the tyre
  EXPECT_EQ(w.window_s, 2.0e-5);
  EXPECT_EQ(w.tyre_substeps, 1);
  EXPECT_EQ(std::string(coupler::coupling_window_reason(w)), "common step: the smaller stable step");
}

TEST(CouplerCouplingWindow, SummaryNamesTheWindowAndWhatEachPeerProposed) {
  const nlohmann::json s = coupler::time_step_summary(coupler::choose_coupling_window(2.5e-6, 2e-5, sc::MULTIRATE));
  EXPECT_EQ(s["coupling_window_s"], 2e-5);
  EXPECT_EQ(s["agreed_dt_s"], 2e-5);
  EXPECT_EQ(s["tyre_substeps"], 8);
  EXPECT_EQ(s["tyre_proposed_dt_s"], 2.5e-6);
  EXPECT_EQ(s["terrain_proposed_dt_s"], 2e-5);
  EXPECT_NE(s["scheme"].get<std::string>().find("multi-rate"), std::string::npos);
}

TEST(CouplerCouplingWindow, BothPeersMustProposeAStep) {
  for (const auto& [tyre, terrain] : {std::pair{0.0, 1e-5}, std::pair{1e-6, -1.0}, std::pair{1e-6, std::nan("")}}) {
    try {
      coupler::choose_coupling_window(tyre, terrain, sc::MULTIRATE);
      ADD_FAILURE() << "accepted " << tyre << ", " << terrain;
    } catch (const cosim::Error& e) {
      EXPECT_NE(std::string(e.what()).find("must both propose a stable step"), std::string::npos) << e.what();
    }
  }
}
