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

// Energy balance. Energy the integration loses (or creates) without booking it acts on
// the rolling tyre like a rolling-resistance moment of its own: E over the angle rolled
// theta is a moment E / theta, and it shows in the road force Fx. So that it is at most
// kMomentTolerance of the moment the test measures, |Fx| h, the balance
// KE + IE - E0 - W (booked work of every load, damping and contact) must stay within
//   |balance| <= kMomentTolerance |Fx| h theta.
// Free rolling: about 0.05 x 2.2 N m x 3 rad = 0.33 J; today -0.03 J, almost all of it
// from the loading stage (dynamic relaxation); it does not grow while rolling.
// Booking the pressure and contact work with the velocity at t - dt/2 instead of t lost
// 0.5 J here, growing with the distance rolled, and failed this bound.
void expect_energy_balance_closed(const nlohmann::json& results) {
  const double balance = results["energy_balance_J"];
  const double theta = 2.0 * M_PI * results["rolling_revolutions"].get<double>();
  const double moment = std::fabs(results["road_longitudinal_force_moment_Nm"].get<double>());
  const double bound = kMomentTolerance * moment * theta;
  std::printf("energy balance %.4f J, bound %.4f J (5 %% of %.2f N m over %.2f rad)\n", balance, bound, moment, theta);
  EXPECT_LT(std::fabs(balance), bound) << (balance > 0 ? "energy created" : "energy lost");
}

// 30 mm elements, 36 divisions (4,968 hexahedra); 0.45 s of rolling averaged over
// the last 0.25 s (0.3 revolution, many periods of the rim-tyre torsional mode).
// Each run sets the drive torque.
const tyre_support::Variation roll{"tyre_rolling_road",
                                   {"tyre.mesh.element_size_m=0.03", "tyre.tread.pitch_count=36",
                                    "tyre.stages.rolling_s=0.45", "tyre.stages.average_last_s=0.25"},
                                   "tyre.rim.drive_torque_Nm"};

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
  expect_energy_balance_closed(f);
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
  expect_energy_balance_closed(d);
  // The rim holds the tyre at its prescribed speed: the only longitudinal forces on
  // the tyre are the road's and the rim's (the inflation pressure has no x
  // resultant: the cavity's openings, the bead circles, lie in planes y = const), so
  // over the window their means differ by the tyre's momentum change over it
  // alone, which a steady roll keeps small: measured 0.74 % (8 N of 1,106 N). The
  // 36 pitches pass the contact about 11 times in the 0.25 s window and the tyre's
  // momentum swings with each passage; the unfinished passage is what remains.
  // Bound 1 %; the force summed over the wrong nodes (the tread's, or the rim
  // node's own) is off by all of it.
  const double fx = d["road_longitudinal_force_N"];
  EXPECT_NEAR(d["rim_longitudinal_force_N"].get<double>(), fx, 0.01 * std::fabs(fx));
}

}  // namespace
