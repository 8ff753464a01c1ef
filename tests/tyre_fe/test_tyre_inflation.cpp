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

// The 3D growth is the crown radius's time mean over the transfer check: the
// transferred tyre breathes undamped about its 3D equilibrium, and the radius at
// the check's end alone swings by +-7 % over 12 ms on the shipped scene (it gave
// -1.09 % at the shipped 3 ms check, -3.0 % at 12 ms, while the mean stays
// within 0.3 %).
void expect_transfer_at_rest(const std::vector<std::string>& sets, const std::string& name) {
  const auto out = tyre_support::scratch(name);
  const auto s = tyre_support::run(tyre_support::scene_path("tyre_inflation"), sets, out);
  ASSERT_EQ(s["status"], "completed");
  const auto& r = s["results"];
  const double axi = r["axisym_radial_growth_m"], growth3d = r["radial_growth_3d_m"];
  std::printf("%s: radial growth axisymmetric %.4f mm, 3D %.4f mm (%.3f %%; at the end %.4f mm); KE after "
              "transfer %.3e J (max %.3e J), IE %.3f J\n", name.c_str(), axi * 1e3, growth3d * 1e3,
              r["radial_growth_difference_percent"].get<double>(), r["radial_growth_3d_end_m"].get<double>() * 1e3,
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

TEST(TyreInflation, RevolvedModelKeepsTheAxisymmetricGrowthAndStaysAtRest) {
  expect_transfer_at_rest(kCoarse, "tyre_inflation");
}

// The shipped scene as a user runs it (8 mm, 120 divisions, 3 ms check).
TEST(TyreInflation, TheShippedSceneKeepsTheAxisymmetricGrowth) {
  expect_transfer_at_rest({}, "tyre_inflation_shipped");
}

}  // namespace
