// The container floor's contact with the snow (ground_friction.cpp,
// boundaries.cpp; docs/sph.md "The ground under the snow") against the closed
// form of a rigid block on an inclined plane with Coulomb friction, kept with
// its source in ground_friction_block_reference.csv:
//   tan(theta) <= mu: the block stays;
//   tan(theta) >  mu: it slides with a = g (sin theta - mu cos theta);
//   frictionless: a = g sin theta; a no-slip (bonded) floor: it stays.
// The incline is the floor under gravity tilted by theta along +x (the
// block's scene, test_ground_friction.textproto: stiff elastic snow, 8 x 4 x 4
// particles of 10 mm, a slab in y between frictionless mirror walls).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cosim/csv.hpp"
#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"
#include "test_support.hpp"

namespace {

constexpr double g = 9.81;

struct BlockMotion {
  double displacement_m = 0.0;     // of the block's centre of mass along x, at the end
  double acceleration_m_s2 = 0.0;  // of its centre of mass along x, over the last three quarters
  double energy_error = 0.0;       // the balance's relative error at the end
  double friction_dissipation_J = 0.0;
  double friction_work_J = 0.0;  // mu M g cos(theta) times the distance slid
};

double momentum_x(const snow_sph::Particles& p) {
  double px = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) px += p.mass[i] * p.vx[i];
  return px;
}

double centre_of_mass_x(const snow_sph::Particles& p, double& mass) {
  double mx = 0.0;
  mass = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) mx += p.mass[i] * p.x[i], mass += p.mass[i];
  return mx / mass;
}

// The block for `end_s` under gravity tilted by atan(tan_theta), on a floor of
// `kind` with coefficient mu (COULOMB).
BlockMotion slide(double tan_theta, const std::string& kind, double mu, double end_s) {
  const double theta = std::atan(tan_theta);
  std::vector<std::string> sets = {"sph.gravity_m_per_s2.x=" + std::to_string(g * std::sin(theta)),
                                   "sph.gravity_m_per_s2.z=" + std::to_string(-g * std::cos(theta)),
                                   "sph.container.floor.kind=" + kind};
  if (kind == "COULOMB") sets.push_back("sph.container.floor.friction_coefficient=" + std::to_string(mu));
  const auto loaded =
      snow_sph::load_sph_scene(test_support::source_dir() + "/tests/snow_sph/test_ground_friction.textproto", sets);
  snow_sph::Model model = snow_sph::build_model(loaded->message);
  snow_sph::Solver solver(model);
  solver.initialise();
  double mass = 0.0;
  const double x0 = centre_of_mass_x(model.particles, mass);
  // The acceleration is the momentum's change over the last three quarters:
  // the first quarter lets the release's elastic waves (the block's height
  // over its sound speed, 2 ms) die down under the artificial viscosity.
  while (solver.time() < 0.25 * end_s) solver.step();
  const double p1 = momentum_x(model.particles), t1 = solver.time();
  while (solver.time() < end_s) solver.step();
  BlockMotion motion;
  motion.acceleration_m_s2 = (momentum_x(model.particles) - p1) / mass / (solver.time() - t1);
  motion.displacement_m = centre_of_mass_x(model.particles, mass) - x0;
  motion.energy_error = solver.energy().relative_error();
  motion.friction_dissipation_J = solver.energy().ground_friction_dissipation;
  motion.friction_work_J = mu * mass * g * std::cos(theta) * motion.displacement_m;
  return motion;
}

// Each case of the reference over 0.2 s (free sliding at the cases' tilt
// covers g sin(theta) t^2 / 2 = 88 mm in it).
// - Stays: the block's centre moves less than 1 mm: what holding leaves is
//   its elastic shear (rho g sin(theta) H^2 / (2 G), 0.04 mm) and its
//   settling on the floor at the release (0.02 mm measured), and a block that
//   slipped at a tenth of the free acceleration would move 9 mm.
// - Slides: the acceleration within 1 % of the closed form. The friction's
//   bound is mu times the images' push on the block, which by the momentum
//   balance is its weight's normal part; what is left is the block's rocking
//   after the release, which moves load between its ends (0.03 % measured).
//   The friction's work (booked as ground_friction_dissipation) within 1 % of
//   mu N times the distance slid, and the balance closed within 1 %.
TEST(GroundFriction, ABlockOnTheFloorUnderTiltedGravityMovesAsTheRigidBlockOnAnIncline) {
  const cosim::CsvTable reference =
      cosim::read_csv(test_support::source_dir() + "/tests/snow_sph/ground_friction_block_reference.csv");
  ASSERT_EQ(reference.rows.size(), 4u);
  for (const auto& row : reference.rows) {
    const std::string name = reference.field(row, "case"), kind = reference.field(row, "floor");
    const double tan_theta = std::stod(reference.field(row, "tan_theta"));
    const double mu = std::stod(reference.field(row, "mu"));
    const double expected = std::stod(reference.field(row, "closed_form_acceleration_m_per_s2"));
    const BlockMotion m = slide(tan_theta, kind, mu, 0.2);
    if (expected == 0.0) {
      EXPECT_LT(std::abs(m.displacement_m), 1e-3) << name;
      continue;
    }
    EXPECT_NEAR(m.acceleration_m_s2, expected, 0.01 * expected) << name;
    EXPECT_LT(m.energy_error, 0.01) << name;
    if (kind == "COULOMB")
      EXPECT_NEAR(m.friction_dissipation_J, m.friction_work_J, 0.01 * m.friction_work_J) << name;
    else
      EXPECT_EQ(m.friction_dissipation_J, 0.0) << name;  // only a Coulomb floor books friction
  }
}

}  // namespace
