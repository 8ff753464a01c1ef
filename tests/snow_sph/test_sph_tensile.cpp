// Water in tension and the tensile instability (Swegle, Hicks & Attaway 1995):
// with the cubic kernel, particles under negative pressure attract each other
// at short range and clump in pairs and knots. In the sliding block's run a
// splash under -15 kPa clumped eight particles within 0.3 mm (spacing 1 mm),
// which then blew up at a wall. Monaghan's (2000) artificial stress
// (sph.artificial_stress_epsilon, eps = 0.2 as in that paper) adds a short-range
// repulsion eps |p| / rho^2 f^4 between particles in tension.
#include <gtest/gtest.h>

#include <string>

#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"
#include "test_support.hpp"

namespace {

// Two water particles alone (no wall within reach, no gravity) at `distance`
// apart, both at 2 % below the reference density (p = -rho0 c^2 0.02 = -18 kPa
// at c = 30 m/s): the acceleration of the first along the line to the second
// (> 0: towards it, they attract).
double pull_towards_each_other(double distance_in_dx, double epsilon) {
  const auto loaded = snow_sph::load_sph_scene(
      test_support::source_dir() + "/tests/snow_sph/test_sph_tensile.textproto",
      {"sph.blocks[0].region.max.x=0.0801", "sph.blocks[0].region.max.y=0.0751", "sph.blocks[0].region.max.z=0.0751"});
  snow_sph::Model model = snow_sph::build_model(loaded->message);
  model.settings.artificial_stress_epsilon = epsilon;
  snow_sph::Particles& p = model.particles;
  EXPECT_EQ(p.n_real, 2u);
  p.x[1] = p.x[0] + distance_in_dx * model.settings.spacing;
  p.y[1] = p.y[0], p.z[1] = p.z[0];
  for (std::size_t i = 0; i < 2; ++i) p.density[i] *= 0.98;
  snow_sph::Solver solver(model);
  solver.prepare();
  EXPECT_LT(p.pressure[0], -17e3);
  EXPECT_LT(p.pressure[1], -17e3);
  return p.ax[0];
}

// Without the artificial stress the pair in tension attracts at every distance
// inside the kernel, most strongly near half a spacing, where the cubic
// kernel's gradient peaks: nothing stops them closing up (the clumps of the
// block's splash). The artificial stress scales the same kernel gradient by
// eps f^4, f = W(r) / W(dx): with eps = 0.2 the pair repels where eps f^4 > 1,
// inside 0.76 dx for the cubic kernel at h = 1.2 dx, and still attracts at a
// spacing and beyond (f <= 1), so the water's tension is not taken away.
TEST(TensileInstability, ArtificialStressTurnsTheShortRangeAttractionOfWaterInTensionIntoRepulsion) {
  for (double d : {0.3, 0.5, 0.6}) {
    EXPECT_GT(pull_towards_each_other(d, 0.0), 0.0) << d << " dx, without";
    EXPECT_LT(pull_towards_each_other(d, 0.2), 0.0) << d << " dx, with";
  }
  for (double d : {1.0, 1.5}) {
    EXPECT_GT(pull_towards_each_other(d, 0.0), 0.0) << d << " dx, without";
    EXPECT_GT(pull_towards_each_other(d, 0.2), 0.0) << d << " dx, with";
  }
}

}  // namespace
