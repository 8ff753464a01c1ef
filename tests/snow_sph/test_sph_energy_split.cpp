// The split of the work done on the terrain (snow_sph/energy_split.hpp,
// docs/sph.md "Where the work done on the terrain goes"): the parts sum to the
// lumped terms they split, the split closes to the same balance, and a term
// the scene switches off books nothing. The case: test_sph_substeps's cube of
// soft snow, struck by a plate (a coupled surface) at 3 m/s and held.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "plate_surface.hpp"
#include "snow_sph/energy_split.hpp"
#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"
#include "test_support.hpp"

namespace {

const std::string kScene = test_support::source_dir() + "/tests/snow_sph/test_sph_substeps.textproto";

using snow_sph_test::plate;

// The cube on the floor under gravity, the plate driven 30 mm into it at 3 m/s and held, 30 ms.
snow_sph::EnergyBalance strike(const std::vector<std::string>& sets) {
  std::vector<std::string> all = {"sph.gravity_m_per_s2.z=-9.81", "sph.blocks[0].region.min.z=0",
                                  "sph.blocks[0].region.max.z=0.1"};
  all.insert(all.end(), sets.begin(), sets.end());
  const auto loaded = snow_sph::load_sph_scene(kScene, all);
  snow_sph::Model model = snow_sph::build_model(loaded->message);
  snow_sph::Solver solver(model);
  const snow_sph::SurfaceContactParameters contact = snow_sph_test::couple_to_surface(solver, model);
  const double window = 0.5 * solver.stability_limit_dt();
  model.settings.coupling_window_s = window;
  const double top = 0.1 + contact.particle_radius_m, stop = top - 0.03, speed = 3.0;
  auto surface_at = [&](double t) {
    const double z = std::max(stop, top - speed * t);
    return plate(z, z > stop ? -speed : 0.0);
  };
  snow_sph::ContactSurface surface = surface_at(0.0);
  solver.contact_surface(&surface, 0);
  solver.initialise();
  for (std::uint64_t n = 1; n * window <= 0.03; ++n) {
    solver.advance_to_exchange();
    surface = surface_at(solver.time());
    solver.contact_surface(&surface, n);
    solver.finish_window();
  }
  EXPECT_TRUE(solver.finite());
  return solver.energy();
}

std::map<std::string, double> by_key(const snow_sph::EnergyBalance& e) {
  std::map<std::string, double> m;
  for (const auto& v : snow_sph::energy_split(e)) m[v.key] = v.value;
  m["contact_dissipation_J"] = e.contact_dissipation;
  return m;
}

// Tolerances: each part is summed per step from per-particle powers that add
// up to the lumped power exactly in real arithmetic; only the order of the
// floating-point sums differs (a few ulps per step over some 10^3 steps), so
// 1e-9 of the lumped term's size is far above round-off and far below any
// missing term (the smallest booked here is above 1e-4 of the largest).
TEST(SphEnergySplit, PartsSumToTheLumpedTermsAndTheBalanceCloses) {
  const snow_sph::EnergyBalance e = strike({"sph.quasi_static_damping_per_s=50"});
  EXPECT_GT(e.plastic_dissipation, 0.0);
  EXPECT_GT(e.artificial_viscous, 0.0);
  EXPECT_GT(e.damping, 0.0);
  EXPECT_GT(e.surface_friction + e.surface_damping, 0.0);
  EXPECT_NEAR(e.plastic_cap + e.plastic_shear, e.plastic_dissipation, 1e-9 * e.plastic_dissipation);
  EXPECT_NEAR(e.artificial_viscous + e.damping + e.water_viscous, e.viscous_dissipation, 1e-9 * e.viscous_dissipation);
  EXPECT_EQ(e.water_viscous, 0.0);  // snow only: the Morris loop never runs
  EXPECT_NEAR(e.gravity_work + e.wall_work + e.body_work + e.resting_terrain_work + e.surface_work_on_particles,
              e.external_work, 1e-9 * std::fabs(e.external_work));
  // The split's "went to" less its work done is the balance of the lumped terms.
  const auto m = by_key(e);
  double went_to = 0.0;
  for (const auto& t : snow_sph::terrain_energy_split().went_to) went_to += m.at(t.key);
  EXPECT_NEAR(went_to - m.at("work_on_terrain_J"), m.at("balance_J"), 1e-9 * m.at("work_on_terrain_J"));
  // The balance itself: within 2 % of the work done (the bar for the runs).
  EXPECT_LT(std::fabs(m.at("balance_J")), 0.02 * m.at("work_on_terrain_J"));
}

TEST(SphEnergySplit, NoDampingBooksNoDampingWork) {
  const snow_sph::EnergyBalance e = strike({});  // the scene has no quasi-static damping
  EXPECT_EQ(e.damping, 0.0);
  EXPECT_GT(e.artificial_viscous, 0.0);
}

}  // namespace
