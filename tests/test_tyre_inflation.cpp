// Inflation (issue: tyre_fe, item 1): the axisymmetric model inflated to 200 kPa
// and the 3D model revolved from it must agree on the radial growth of the tread
// centre (within 0.5 %), and the 3D model must start at rest.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "tyre_support.hpp"

namespace {

// Coarser than the scene (same physics) to keep the suite fast.
const std::vector<std::string> kCoarse = {"tyre.mesh.element_size_m=0.012", "tyre.tread.elements_per_pitch=1",
                                          "tyre.stages.transfer_check_s=0.0015"};

TEST(TyreInflation, RevolvedModelKeepsTheAxisymmetricGrowthAndStaysAtRest) {
  const auto out = tyre_support::scratch("tyre_inflation");
  const auto s = tyre_support::run(tyre_support::scene_path("tyre_inflation"), kCoarse, out);
  ASSERT_EQ(s["status"], "completed");
  const auto& r = s["results"];
  const double axi = r["axisym_radial_growth_m"], growth3d = r["radial_growth_3d_m"];
  std::printf("radial growth: axisymmetric %.4f mm, 3D %.4f mm (%.3f %%); KE after transfer %.3e J "
              "(max %.3e J), IE %.3f J\n", axi * 1e3, growth3d * 1e3, r["radial_growth_difference_percent"].get<double>(),
              r["kinetic_energy_after_transfer_J"].get<double>(), r["max_kinetic_energy_after_transfer_J"].get<double>(),
              r["internal_energy_after_transfer_J"].get<double>());
  // A 235/75R15 passenger tyre grows by a few millimetres at the crown when inflated.
  EXPECT_GT(axi, 0.5e-3);
  EXPECT_LT(axi, 10e-3);
  EXPECT_LT(std::fabs(growth3d - axi) / axi, 0.005);  // issue: equal within 0.5 %
  // At rest: inflating the 3D model suddenly would turn about half of the strain
  // energy into kinetic energy; the transferred state must stay within 1 % of that
  // energy scale. What remains (0.3 % here) is the O(h/R) difference between the
  // one-point quad and the revolved one-point hex (docs/tyre_fe.md).
  EXPECT_LT(r["max_kinetic_energy_after_transfer_J"].get<double>(),
            0.01 * r["internal_energy_after_transfer_J"].get<double>());
}

}  // namespace
