// Linear Us-Up Hugoniot EOS (thesis Table 4.1) against its closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "snow_sph/water_eos.hpp"

TEST(WaterEos, LinearUsUpWithZeroSlopeIsLinearInEta) {
  snow_sph::WaterEos eos;  // rho0 = 996, c0 = 1500, s = 0 (thesis Table 4.1)
  for (double rho : {990.0, 996.0, 1000.0, 1010.0}) {
    const double eta = 1.0 - 996.0 / rho;
    EXPECT_NEAR(eos.pressure(rho), 996.0 * 1500.0 * 1500.0 * eta, 1e-9 * 996.0 * 1500.0 * 1500.0);
    EXPECT_NEAR(eos.density_for_pressure(eos.pressure(rho)), rho, 1e-9 * rho);
  }
  EXPECT_EQ(eos.pressure(996.0), 0.0);
  EXPECT_NEAR(eos.sound_speed(996.0), 1500.0, 1e-9);
}

TEST(WaterEos, HugoniotSlopeStiffensCompression) {
  snow_sph::WaterEos eos;
  eos.s = 1.79;  // a typical water slope, for the s != 0 branch
  const double rho = 1050.0, eta = 1.0 - 996.0 / rho;
  const double expected = 996.0 * 1500.0 * 1500.0 * eta / ((1 - 1.79 * eta) * (1 - 1.79 * eta));
  EXPECT_NEAR(eos.pressure(rho), expected, 1e-9 * expected);
  EXPECT_NEAR(eos.density_for_pressure(expected), rho, 1e-8 * rho);
}

TEST(WaterEos, EnergyIsIntegralOfPressureWork) {
  // de/drho = p / rho^2 (reversible compression).
  for (double s : {0.0, 1.0}) {
    snow_sph::WaterEos eos;
    eos.s = s;
    const double rho = 1003.0, d = 1e-3;
    const double dedrho = (eos.energy_per_mass(rho + d) - eos.energy_per_mass(rho - d)) / (2 * d);
    EXPECT_NEAR(dedrho, eos.pressure(rho) / (rho * rho), 1e-3 * eos.pressure(rho) / (rho * rho));
  }
}

// The tension limit (WaterMaterial.tension_limit_Pa): the pressure follows the
// law down to -limit and stays there, and the energy stays the integral of the
// pressure's work through the limit (de/drho = p / rho^2 on both sides of it),
// so the energy balance still closes. A splash in the hydroplaning run reached
// 446 kg/m^3, where the law alone gives -27.6 MPa at c0 = 150 m/s.
TEST(WaterEos, TheTensionLimitHoldsThePressureAndKeepsTheEnergyItsWork) {
  for (double s : {0.0, 1.79}) {
    snow_sph::WaterEos eos;
    eos.c0 = 150.0, eos.s = s, eos.tension_limit = 99e3;
    const snow_sph::WaterEos unlimited = [&] { auto u = eos; u.tension_limit = 0; return u; }();
    EXPECT_LT(unlimited.pressure(446.0), -2e6);  // -27.6 MPa with s = 0, -2.7 MPa with 1.79
    EXPECT_EQ(eos.pressure(446.0), -99e3);
    const double rho_lim = eos.density_for_pressure(-99e3);
    // Beyond the limit the sound speed stays the limit's (the law alone with
    // s = 0: 3,200 m/s at 46 kg/m^3). The limit's strain is 99 kPa / (rho0 c0^2)
    // = 0.44 %, which lowers sqrt(dp/drho) by up to 1.5 % with s = 1.79
    // ((1 + s e) / (1 - s e)^3 under the root): 2 % of c0 is that bound with room.
    EXPECT_EQ(eos.sound_speed(46.0), eos.sound_speed(rho_lim));
    EXPECT_NEAR(eos.sound_speed(46.0), 150.0, 3.0);
    if (s == 0.0) {
      EXPECT_GT(unlimited.sound_speed(46.0), 1000.0);
    }
    EXPECT_EQ(eos.pressure(1000.0), unlimited.pressure(1000.0));    // compression untouched
    EXPECT_EQ(eos.pressure(rho_lim + 0.5), unlimited.pressure(rho_lim + 0.5));  // tension above the limit too
    for (double rho : {rho_lim + 0.2, rho_lim - 0.2, 900.0, 446.0}) {
      const double d = 1e-4;
      const double dedrho = (eos.energy_per_mass(rho + d) - eos.energy_per_mass(rho - d)) / (2 * d);
      const double expected = eos.pressure(rho) / (rho * rho);
      // Central difference of a smooth (s = 0: quadratic, then linear) function;
      // the s != 0 branch integrates with 16 midpoints: 1e-3 covers both.
      EXPECT_NEAR(dedrho, expected, 1e-3 * std::fabs(expected)) << "s " << s << " rho " << rho;
    }
  }
}
