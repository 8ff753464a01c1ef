// Water pinched between a facet and a wall (snow_sph/surface_contact.hpp,
// SurfaceContactParameters::drain_film_m; docs/water.md, "Films thinner than a
// particle"). A film thinner than half a particle cannot be resolved by
// particles: before this rule a tread pressed onto the road through water
// crushed the last particles between itself and the floor with the penalty's
// capped force, and the terrain's step collapsed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"
#include "snow_sph/surface_contact.hpp"
#include "test_support.hpp"

namespace {

using snow_sph::ContactSurface;
using snow_sph::SurfaceContactParameters;
using snow_sph::SurfaceContactResult;

constexpr double kRadius = 0.0025;

// One facet, its outward normal along -z (facing the floor z = 0), its corners
// at height z over [x0, x1] x [-0.01, 0.01]; tilted: the far edge raised by `rise`.
ContactSurface facet_over_floor(double z, double rise = 0.0) {
  ContactSurface s;
  const double xs[4] = {-0.01, -0.01, 0.01, 0.01}, ys[4] = {-0.01, 0.01, 0.01, -0.01};
  for (int a = 0; a < 4; ++a) {
    s.x.push_back(xs[a]), s.y.push_back(ys[a]), s.z.push_back(z + (xs[a] > 0 ? rise : -rise));
    s.vx.push_back(0), s.vy.push_back(0), s.vz.push_back(0);
  }
  s.facet_nodes = {0, 1, 2, 3};  // (x2 - x0) x (x3 - x1) along -z
  s.friction_coefficient = {0.0};
  return s;
}

SurfaceContactParameters floor_params() {
  SurfaceContactParameters p;
  p.particle_radius_m = kRadius;
  p.stiffness_N_per_m = 1e4;
  p.walls.push_back({2, 0.0, 1});
  p.drain_film_m = kRadius;
  return p;
}

struct One {
  SurfaceContactResult result;
  double az = 0.0;
};
One press(const ContactSurface& s, double particle_z, std::uint8_t drainable) {
  double x = 0.0, y = 0.0, z = particle_z, v = 0.0, m = 1e-4, ax = 0, ay = 0, az = 0;
  One o;
  snow_sph::surface_contact(s, floor_params(), 1, &x, &y, &z, &v, &v, &v, &m, 1e-5, &ax, &ay, &az, o.result,
                            nullptr, nullptr, &drainable);
  o.az = az;
  return o;
}

// The film is the facet's height above the floor along the floor's normal
// through the particle: a flat facet 1.2 radii above the floor leaves room for
// more than half the particle, 0.8 radii does not.
TEST(Drain, AWaterParticleUnderAFacetLowerThanItsRadiusAboveTheWallIsDrainedWithoutForce) {
  const One open = press(facet_over_floor(1.2 * kRadius), 0.6 * kRadius, 1);
  EXPECT_TRUE(open.result.drained.empty());
  EXPECT_LT(open.az, 0.0);  // pushed down, towards the floor
  const One closed = press(facet_over_floor(0.8 * kRadius), 0.4 * kRadius, 1);
  ASSERT_EQ(closed.result.drained.size(), 1u);
  EXPECT_EQ(closed.result.drained[0], 0u);
  EXPECT_EQ(closed.az, 0.0);
  EXPECT_EQ(closed.result.total_fz_N, 0.0);
  EXPECT_EQ(closed.result.particles_in_contact[0], 0u);
}

TEST(Drain, OnlyDrainableParticlesAndOnlyUnderFacetsThatFaceTheWall) {
  // Snow (not drainable) stays and is pushed.
  const One snow = press(facet_over_floor(0.8 * kRadius), 0.4 * kRadius, 0);
  EXPECT_TRUE(snow.result.drained.empty());
  EXPECT_LT(snow.az, 0.0);
  // A facet tilted 50 degrees from the floor (its normal 50 degrees from -z,
  // beyond the 45 degrees of facing) does not pinch against it, however low.
  const double rise = 0.01 * std::tan(50.0 * M_PI / 180.0);
  const One steep = press(facet_over_floor(0.5 * kRadius, rise), 0.4 * kRadius, 1);
  EXPECT_TRUE(steep.result.drained.empty());
  // Tilted 30 degrees it does: the film along the floor's normal is the gap over cos 30.
  const double low = 0.01 * std::tan(30.0 * M_PI / 180.0);
  const One gentle = press(facet_over_floor(0.5 * kRadius, low), 0.4 * kRadius, 1);
  EXPECT_EQ(gentle.result.drained.size(), 1u);
}

// A 4 x 4 cm plate pressed at 1 m/s through 2 cm of water onto the floor and
// held 1 mm above it: the water leaves the gap (sideways while it can, drained
// once the film is thinner than half a particle) and the mass is accounted for.
TEST(Drain, APlatePressedThroughAWaterLayerOntoTheFloorSqueezesItOut) {
  const auto loaded =
      snow_sph::load_sph_scene(test_support::source_dir() + "/tests/snow_sph/test_sph_drain.textproto", {});
  snow_sph::Model model = snow_sph::build_model(loaded->message);
  snow_sph::Solver solver(model);
  SurfaceContactParameters contact;
  contact.particle_radius_m = 0.5 * model.settings.spacing;
  // The scenes' penalty: the water's bulk modulus over a particle (rho c^2 dx).
  contact.stiffness_N_per_m = 1000.0 * 30.0 * 30.0 * model.settings.spacing;
  solver.couple(contact);
  snow_sph::Particles& p = model.particles;
  double initial_kg = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) initial_kg += p.mass[i];

  // The plate: 4 x 4 facets of 1 cm over [0.03, 0.07]^2, outward normal -z.
  ContactSurface plate;
  const int n = 5;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      plate.x.push_back(0.03 + 0.01 * i), plate.y.push_back(0.03 + 0.01 * j), plate.z.push_back(0.025);
      plate.vx.push_back(0), plate.vy.push_back(0), plate.vz.push_back(0);
    }
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const std::uint32_t a = i * n + j;
      plate.facet_nodes.insert(plate.facet_nodes.end(), {a, a + 1, a + 1 + n, a + n});
      plate.friction_coefficient.push_back(0.0);
    }
  solver.prepare();
  model.settings.coupling_window_s = model.settings.cfl * solver.stability_limit_dt();
  const double speed = 1.0, parked = 0.001, hold_s = 0.01;
  double t = 0.0;
  std::uint64_t exchange = 0;
  solver.contact_surface(&plate, exchange++);
  solver.initialise();
  const double end = (0.025 - parked) / speed + hold_s;
  while (t < end) {
    solver.step();
    t = solver.time();
    const double z = std::max(parked, 0.025 - speed * t);
    for (std::size_t k = 0; k < plate.z.size(); ++k) plate.z[k] = z, plate.vz[k] = z > parked ? -speed : 0.0;
    solver.contact_surface(&plate, exchange++);
  }
  ASSERT_TRUE(solver.finite());
  // Mass: what stays plus what drained is what there was (round-off only).
  double left_kg = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) left_kg += p.mass[i];
  EXPECT_NEAR(left_kg + solver.drained_mass_kg(), initial_kg, 1e-12 * initial_kg);
  EXPECT_GT(solver.drained_particles(), 0u);
  // No particle left under the plate (inside its footprint less one radius).
  int under = 0;
  for (std::size_t i = 0; i < p.n_real; ++i)
    if (p.x[i] > 0.03 + kRadius && p.x[i] < 0.07 - kRadius && p.y[i] > 0.03 + kRadius && p.y[i] < 0.07 - kRadius &&
        p.z[i] < 0.005)
      ++under;
  EXPECT_EQ(under, 0);
  // The water under the parked plate carries no load: without the rule 12
  // particles stay crushed under it and push it with 135 N (the penalty's cap);
  // 1 N is three times the weight of the 2 cm column the plate stands in (0.31 N),
  // more than the particles at its rim could press up.
  EXPECT_LT(std::abs(solver.surface_loads().total_fz_N), 1.0);
}

// Water thrown out of the open-top box leaves the terrain: the walls are planes
// that go on above the box, and a splash falling back along one of them is not
// a flow the box models (the sliding block's run blew up on such a splash).
TEST(Drain, WaterThrownAboveTheOpenTopOfTheBoxLeavesTheTerrain) {
  const auto loaded =
      snow_sph::load_sph_scene(test_support::source_dir() + "/tests/snow_sph/test_sph_drain.textproto", {});
  snow_sph::Model model = snow_sph::build_model(loaded->message);
  snow_sph::Particles& p = model.particles;
  double initial_kg = 0.0;
  int thrown = 0;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    initial_kg += p.mass[i];
    // The top layer over a 1 x 1 cm patch, thrown up at 5 m/s (it would rise 1.3 m).
    if (p.z[i] > 0.015 && std::abs(p.x[i] - 0.05) < 0.005 && std::abs(p.y[i] - 0.05) < 0.005) p.vz[i] = 5.0, ++thrown;
  }
  ASSERT_EQ(thrown, 4);
  snow_sph::Solver solver(model);
  solver.prepare();
  while (solver.time() < 0.02) solver.step();  // 0.1 m of rise at 5 m/s: past the top at 0.06 m
  ASSERT_TRUE(solver.finite());
  double left_kg = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    left_kg += p.mass[i];
    EXPECT_LE(p.z[i], model.container_max[2]) << i;
  }
  EXPECT_GE(solver.drained_particles(), 4u);
  EXPECT_NEAR(left_kg + solver.drained_mass_kg(), initial_kg, 1e-12 * initial_kg);
}

// WaterMaterial.valid_density_*_ratio: a water particle whose density has left
// the valid range leaves the terrain, counted with the drained water; one inside
// it stays. The range is DualSPHysics's default, 700-1300 kg/m^3 for 1000 (its
// RhopOutMin / RhopOutMax). One step changes a resting layer's densities by far
// less than the margins used here (0.60 and 1.35 against 0.7 and 1.3), so the
// outcome is the rule's, not the step's.
TEST(Drain, WaterWhoseDensityLeavesTheValidRangeLeavesTheTerrain) {
  const auto loaded =
      snow_sph::load_sph_scene(test_support::source_dir() + "/tests/snow_sph/test_sph_drain.textproto", {});
  snow_sph::Model model = snow_sph::build_model(loaded->message);
  for (auto& mat : model.materials) {
    ASSERT_EQ(mat.kind, snow_sph::MaterialModel::Kind::water);
    mat.valid_density_min = 0.7 * mat.density0, mat.valid_density_max = 1.3 * mat.density0;
  }
  snow_sph::Particles& p = model.particles;
  double initial_kg = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) initial_kg += p.mass[i];
  const double rho0 = model.materials[0].density0;
  // Three particles of the top layer: stretched, crushed, and inside the range.
  std::vector<std::uint32_t> top;
  for (std::size_t i = 0; i < p.n_real && top.size() < 3; ++i)
    if (p.z[i] > 0.015) top.push_back(p.id[i]);
  ASSERT_EQ(top.size(), 3u);
  auto index_of = [&](std::uint32_t id) {
    for (std::size_t i = 0; i < p.n_real; ++i)
      if (p.id[i] == id) return static_cast<long>(i);
    return -1L;
  };
  p.density[index_of(top[0])] = 0.60 * rho0;
  p.density[index_of(top[1])] = 1.35 * rho0;
  p.density[index_of(top[2])] = 0.95 * rho0;
  const std::size_t before = p.n_real;
  snow_sph::Solver solver(model);
  solver.prepare();
  solver.step();
  ASSERT_TRUE(solver.finite());
  EXPECT_EQ(index_of(top[0]), -1);
  EXPECT_EQ(index_of(top[1]), -1);
  EXPECT_NE(index_of(top[2]), -1);
  EXPECT_EQ(solver.density_out_particles(), 2u);
  EXPECT_EQ(solver.drained_particles(), 2u);
  EXPECT_EQ(p.n_real, before - 2);
  double left_kg = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) left_kg += p.mass[i];
  EXPECT_NEAR(left_kg + solver.drained_mass_kg(), initial_kg, 1e-12 * initial_kg);
}

}  // namespace
