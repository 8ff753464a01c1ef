// Linear Us-Up Hugoniot EOS (thesis Table 4.1) against its closed form.
#include <gtest/gtest.h>

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
