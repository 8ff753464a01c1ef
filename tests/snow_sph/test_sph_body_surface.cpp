// The terrain's surface, the datum of the plate's and the tyre's sinkage.
//
// The plate's sinkage is measured from the snow's surface under it, as the
// laboratory's plate sinkage was (thesis 3.2). That surface is the top of the
// particle lattice: a block's region is filled with whole layers of dx
// (snow_sph/scene.cpp), so when dx does not divide the region's height the
// snow's top lies below the region's top, and a plate started at the region's
// top falls through the gap before it touches. In the plate scene's 0.5 m slab
// 14 mm particles make 35 layers, 0.49 m: the plate's displacement there is its
// sinkage plus 1 cm (the convergence study's 14 mm case, docs/validation.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "coupler/scene_checks.hpp"
#include "snow_sph/scene.hpp"
#include "test_support.hpp"

namespace {

double surface_under_plate(double dx, double& lattice_top) {
  const auto loaded = snow_sph::load_sph_scene(test_support::source_dir() + "/configs/scenes/plate_sinkage.textproto",
                                               {"sph.particle_spacing_m=" + std::to_string(dx)});
  const snow_sph::Model model = snow_sph::build_model(loaded->message);
  const snow_sph::RigidBody& plate = model.bodies.at(0);
  const snow_sph::Particles& p = model.particles;
  // The particles' own top under the plate: the highest centre plus dx / 2, the
  // radius the plate's contact gives a particle (body_contact, snow_sph/src/rigid_bodies.cpp).
  lattice_top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.n_real; ++i)
    if (std::hypot(p.x[i] - plate.x, p.y[i] - plate.y) <= plate.radius)
      lattice_top = std::max(lattice_top, p.z[i] + 0.5 * dx);
  return plate.surface_z;
}

TEST(SphBodySurface, SinkageIsMeasuredFromTheTopOfTheParticlesUnderThePlate) {
  for (const double dx : {0.02, 0.014, 0.01}) {
    double top = 0.0;
    const double surface = surface_under_plate(dx, top);
    // The same lattice read two ways (the block's layers, the particles made from
    // them): they differ by rounding only.
    EXPECT_NEAR(surface, top, 1e-12) << "dx = " << dx;
    // The plate starts at the region's top, 0.5 m: flush with the snow when dx
    // divides 0.5 m (20 and 10 mm), 1 cm above it at 14 mm (35 layers).
    const double gap = 0.5 - surface;
    if (dx == 0.014) EXPECT_NEAR(gap, 0.01, 1e-12);
    else EXPECT_NEAR(gap, 0.0, 1e-12) << "dx = " << dx;
  }
}


// The coupler measures the tyre's sinkage from the same surface. The coarse
// torque and slip studies run the thesis's 0.09 m snow block at 20 mm: four
// layers, 0.08 m, so the snow's top is 1 cm below the region's (z = 0).
TEST(SphBodySurface, TheCouplersTerrainSurfaceIsTheTopOfTheParticles) {
  for (const double dx : {0.02, 0.01}) {
    const auto loaded = snow_sph::load_sph_scene(test_support::source_dir() +
                                                     "/configs/scenes/tyre_torque_snow_thesis.textproto",
                                                 {"sph.particle_spacing_m=" + std::to_string(dx)});
    const snow_sph::Model model = snow_sph::build_model(loaded->message);
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < model.particles.n_real; ++i) top = std::max(top, model.particles.z[i] + 0.5 * dx);
    EXPECT_NEAR(coupler::terrain_surface_z_m(loaded->message), top, 1e-12) << "dx = " << dx;
    EXPECT_NEAR(top, dx == 0.02 ? -0.01 : 0.0, 1e-12) << "dx = " << dx;
  }
}

}  // namespace
