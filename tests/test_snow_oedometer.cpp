// Verification of the SPH snow solver in confined compression: the settlement
// of a soft-snow column under a full-width plate must equal the sum over its
// layers of the material-point response in uniaxial strain (each layer loaded
// from its geostatic state to the plate pressure plus the weight above it).
// This checks SPH equilibrium, continuity and the wall treatment against the
// constitutive model alone.
#include <gtest/gtest.h>

#include <cmath>

#include "snow_sph/mdpc.hpp"
#include "test_support.hpp"

namespace {

// Measured: +4.5 % with the scene's 0.15 s ramp and 150 1/s quasi-static
// damping, +3 % with a 0.5 s ramp and no damping (20 mm particles, 25 layers:
// discretisation). Without damping the fast ramp gives +18 % (dynamic
// overshoot), which this bound rejects.
constexpr double kSettlementTolerance = 0.05;

double reference_settlement(const snow_sph::MdpcParameters& m, double rho, double g, double height,
                            double pressure, int layers) {
  const double nu = m.poisson_ratio, k0 = nu / (1 - nu);
  const double dz = height / layers;
  double settlement = 0.0;
  for (int l = 0; l < layers; ++l) {
    const double depth = (l + 0.5) * dz;
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    s(2, 2) = -rho * g * depth;
    s(0, 0) = s(1, 1) = k0 * s(2, 2);
    double eps = snow_sph::cap_strain_enclosing(m, s);
    const double target = -(pressure + rho * g * depth);  // weight above is conserved
    double strain = 0.0;                                    // logarithmic vertical strain
    const double step = 1e-5;
    while (s(2, 2) > target) {
      Eigen::Matrix3d de = Eigen::Matrix3d::Zero();
      de(2, 2) = -step;
      const Eigen::Matrix3d before = s;
      snow_sph::mdpc_update(m, de, s, eps);
      strain -= step;
      if (s(2, 2) < target) {  // interpolate the last increment
        strain += step * (target - s(2, 2)) / (before(2, 2) - s(2, 2));
        break;
      }
    }
    settlement += dz * (1.0 - std::exp(strain));
  }
  return settlement;
}

TEST(SnowOedometer, SettlementMatchesMaterialPointIntegration) {
  const std::string scene = test_support::source_dir() + "/tests/test_snow_oedometer.textproto";
  const auto s = test_support::run(scene, {}, test_support::scratch("oedometer"));
  const auto loaded = cosim::load_scene(scene);
  const auto mat = snow_sph::material_from_scene(loaded->message.sph().blocks(0).material());
  const double pressure = 1797.6 / (0.2 * 0.2);
  const double expected = reference_settlement(mat.mdpc, 180.0, 9.81, 0.5, pressure, 200);
  const double got = s["results"]["plate_displacement_m"];
  std::printf("oedometer: SPH settlement %.4f m, material-point integration %.4f m\n", got, expected);
  EXPECT_NEAR(got, expected, kSettlementTolerance * expected);
  // At rest at the end: the plate carries its load.
  EXPECT_NEAR(s["results"]["plate_contact_force_z_N"].get<double>(), 1797.6, 0.01 * 1797.6);
  EXPECT_LT(std::abs(s["results"]["plate_velocity_z_m_per_s"].get<double>()), 0.01);
}

}  // namespace
