// Rolling on a rigid road (issue: tyre_fe, item 3), on a coarse mesh to keep the
// suite short. Free rolling: the effective rolling radius lies between the loaded
// radius and the free radius (a rolling tyre's belt is nearly inextensible, so it
// rolls on a radius close to the free one; Pacejka, Tire and Vehicle Dynamics, 2012,
// sec. 7.2), and the energy balance stays closed. Driving torque T: at steady state
// the moment balance of the tyre about the axle gives
//   Fx(T) h = T - M_rr,   M_rr = -Fx(free) h   (free-rolling resistance moment),
// h the rim height above the road (the lever arm of the road force).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "tyre_support.hpp"

namespace {

constexpr double kDriveTorque_Nm = 400.0;
constexpr double kMomentTolerance = 0.05;  // issue: within 5 %
// Energy balance after rolling: no spurious growth (the surplus KE + IE - E0 - W stays
// below 0.1 % of the largest energy); what the integration loses without booking it
// (measured 1.1 % after 1.35 revolutions on the scene's mesh) stays below 1 %.
constexpr double kEnergyGrowthTolerance = 1e-3;
constexpr double kEnergyLossTolerance = 1e-2;

void expect_no_energy_growth(const nlohmann::json& results) {
  const double error = results["energy_balance_error"], balance = results["energy_balance_J"];
  if (balance > 0.0) EXPECT_LT(error, kEnergyGrowthTolerance) << "energy created: " << balance << " J";
  EXPECT_LT(error, kEnergyLossTolerance);
}

// 30 mm elements, 36 divisions (4,968 hexahedra); 0.45 s of rolling averaged over
// the last 0.25 s (0.3 revolution, many periods of the rim-tyre torsional mode).
const std::vector<std::string> kCoarse = {"tyre.mesh.element_size_m=0.03", "tyre.tread.pitch_count=36",
                                          "tyre.stages.rolling_s=0.45", "tyre.stages.average_last_s=0.25"};

nlohmann::json roll(double torque_Nm, const std::string& name) {
  auto sets = kCoarse;
  sets.push_back("tyre.rim.drive_torque_Nm=" + std::to_string(torque_Nm));
  return tyre_support::run(tyre_support::scene_path("tyre_rolling_road"), sets, tyre_support::scratch(name));
}

TEST(TyreRolling, FreeRollingRadiusAndDrivingTorqueBalance) {
  const auto free_run = roll(0.0, "tyre_rolling_free");
  ASSERT_EQ(free_run["status"], "completed");
  const auto& f = free_run["results"];
  const double rolling_radius = f["rolling_radius_m"], loaded = f["loaded_radius_rolling_m"],
               unloaded = f["unloaded_radius_m"];
  std::printf("free rolling: rolling radius %.2f mm (loaded %.2f, free %.2f), Fx %.1f N, RM2 %.2f N m, "
              "energy balance %.3f J (%.2e)\n",
              rolling_radius * 1e3, loaded * 1e3, unloaded * 1e3, f["road_longitudinal_force_N"].get<double>(),
              f["rm2_Nm"].get<double>(), f["energy_balance_J"].get<double>(),
              f["energy_balance_error"].get<double>());
  EXPECT_GT(rolling_radius, loaded);
  EXPECT_LT(rolling_radius, unloaded);
  expect_no_energy_growth(f);
  EXPECT_GT(f["rolling_revolutions"].get<double>(), 0.15);

  const auto driven = roll(kDriveTorque_Nm, "tyre_rolling_torque");
  ASSERT_EQ(driven["status"], "completed");
  const auto& d = driven["results"];
  const double resistance_moment = -f["road_longitudinal_force_moment_Nm"].get<double>();
  const double road_moment = d["road_longitudinal_force_moment_Nm"];
  std::printf("torque %.0f N m: Fx %.1f N, Fx h %.1f N m, T - M_rr %.1f N m (M_rr %.2f N m), "
              "Fx r_rolling %.1f N m, RM2 %.1f N m\n",
              kDriveTorque_Nm, d["road_longitudinal_force_N"].get<double>(), road_moment,
              kDriveTorque_Nm - resistance_moment, resistance_moment,
              d["road_longitudinal_force_N"].get<double>() * d["rolling_radius_m"].get<double>(),
              d["rm2_Nm"].get<double>());
  // The form (force times the rolling radius) and the exact lever arm (rim
  // height): they differ by the forward shift of the vertical force under torque.
  const double net_torque = kDriveTorque_Nm - resistance_moment;
  EXPECT_NEAR(d["road_longitudinal_force_N"].get<double>() * d["rolling_radius_m"].get<double>(), net_torque,
              kMomentTolerance * net_torque);
  EXPECT_NEAR(road_moment, net_torque, kMomentTolerance * net_torque);
  EXPECT_NEAR(d["rm2_Nm"].get<double>(), kDriveTorque_Nm, 0.01 * kDriveTorque_Nm);  // spin at steady state
  expect_no_energy_growth(d);
}

}  // namespace
