// The terrain sub-steps inside a coupling window when its own stable limit
// falls below the window (snow_sph/solver.hpp, docs/coupling.md "The terrain
// sub-steps"), instead of stopping the run. The surface's owner is played here
// by a rigid plate driven at a prescribed speed, exchanged once per window as a
// coupled run does (advance -> surface in -> contact -> complete).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "cosim/scene_io.hpp"
#include "plate_surface.hpp"
#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"
#include "test_support.hpp"

namespace {

const std::string kScene = test_support::source_dir() + "/tests/snow_sph/test_sph_substeps.textproto";

using snow_sph_test::plate;

struct Outcome {
  std::uint64_t windows = 0, substepped = 0;
  std::uint32_t most_substeps = 0;
  double momentum[3] = {0, 0, 0};       // sum m v of the particles at the end [N s]
  double owner_impulse[3] = {0, 0, 0};  // on the particles, as the owner books it: window x force
  double solver_impulse[3] = {0, 0, 0};
  double energy_error = 0.0;
  bool finite = false;
};

// Drives the plate down at `speed` from just above the cube's top to `stop_z`,
// then holds it there, for `duration` s, in windows of `courant` times the
// terrain's stable limit at the start.
Outcome strike(const std::vector<std::string>& sets, double top_z, double speed, double stop_z, double duration,
               double courant) {
  const auto loaded = snow_sph::load_sph_scene(kScene, sets);
  snow_sph::Model model = snow_sph::build_model(loaded->message);
  snow_sph::Solver solver(model);
  const snow_sph::SurfaceContactParameters contact = snow_sph_test::couple_to_surface(solver, model);
  const double window = courant * solver.stability_limit_dt();
  model.settings.coupling_window_s = window;
  const double z0 = top_z + contact.particle_radius_m + 1e-3;  // 1 mm clear of the top particles
  auto surface_at = [&](double t) {
    const double z = std::max(stop_z, z0 - speed * t);
    return plate(z, z > stop_z ? -speed : 0.0);
  };
  snow_sph::ContactSurface surface = surface_at(0.0);
  solver.contact_surface(&surface, 0);
  solver.initialise();
  Outcome out;
  double held[3] = {0, 0, 0};  // force on the particles of the last exchange
  auto hold = [&]() {
    const auto& l = solver.surface_loads();
    held[0] = -l.total_fx_N, held[1] = -l.total_fy_N, held[2] = -l.total_fz_N;
  };
  hold();
  for (std::uint64_t n = 1; n * window <= duration; ++n) {
    solver.advance_to_exchange();
    for (int c = 0; c < 3; ++c) out.owner_impulse[c] += window * held[c];
    surface = surface_at(solver.time());
    solver.contact_surface(&surface, n);
    hold();
    solver.finish_window();
    out.windows = n;
  }
  const snow_sph::Particles& p = model.particles;
  for (std::size_t i = 0; i < p.n_real; ++i)
    out.momentum[0] += p.mass[i] * p.vx[i], out.momentum[1] += p.mass[i] * p.vy[i],
        out.momentum[2] += p.mass[i] * p.vz[i];
  for (int c = 0; c < 3; ++c) out.solver_impulse[c] = solver.surface_impulse_Ns()[c];
  out.substepped = solver.substepped_windows();
  out.most_substeps = solver.most_substeps();
  out.energy_error = solver.energy().relative_error();
  out.finite = solver.finite();
  return out;
}

// A free cube (no gravity, no wall within reach) struck at 30 m/s in windows at
// Courant number 0.95: the struck particles' speed lowers the limit h / (c + |v|)
// below the window within a few windows. The old scheme stopped there.
// The particles' momentum, measured from their velocities, is what the owner
// booked, window by window (window x held force): the pair forces of SPH cancel
// in pairs, so nothing else moves the cube. 1e-9 of the impulse is rounding over
// ~100 steps of 125 particles (~1e-13) with room; kicking the held force with
// the leapfrog mean of two sub-steps instead of the sub-step's length is off by
// half a sub-step's impulse at every change of sub-step length: 3.4 % here.
TEST(TerrainSubsteps, TheParticlesReceiveExactlyWhatTheOwnerBooksOverSubsteppedWindows) {
  Outcome o;
  ASSERT_NO_THROW(o = strike({}, 0.55, 30.0, -1.0, 0.003, 0.95));
  ASSERT_TRUE(o.finite);
  EXPECT_GT(o.substepped, 5u) << "the case must sub-step to test anything";
  EXPECT_GE(o.most_substeps, 4u);  // ceil(0.95 / (0.3 x 0.9...)) at least
  ASSERT_LT(o.owner_impulse[2], -1e-3);  // the plate pushed the cube down
  const double scale = std::fabs(o.owner_impulse[2]);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(o.momentum[c], o.owner_impulse[c], 1e-9 * scale) << c;
    EXPECT_NEAR(o.solver_impulse[c], o.owner_impulse[c], 1e-9 * scale) << c;
  }
  std::printf("free cube: %llu windows, %llu sub-stepped, at most %u sub-steps; impulse %.6e N s\n",
              static_cast<unsigned long long>(o.windows), static_cast<unsigned long long>(o.substepped),
              o.most_substeps, o.owner_impulse[2]);
}

// A cube resting on the floor, with gravity, and the plate driven down at 3 m/s
// (the thesis's rolling speed is 2.78 m/s) until the cube is crushed to 30 % of
// its height, then held: the extreme case (snow pinched between a tread and the
// rigid floor) that stopped the thesis-resolution torque point. In windows at
// Courant number 0.95 it sub-steps in most windows. It must finish with a finite
// state and its energy balance within 1 %, the lower end of Abaqus's guidance
// for explicit runs (1-5 % of the largest energy) and what the coupled runs'
// terrain balance meets (docs/coupling.md). Measured: 0.25 % (0.17 % in windows
// at Courant 0.6 that need no sub-step); with the held force left out of the
// sub-steps it is 64 %.
TEST(TerrainSubsteps, ACubeCrushedOntoTheFloorStaysStable) {
  const std::vector<std::string> on_floor = {"sph.gravity_m_per_s2.z=-9.81", "sph.blocks[0].region.min.z=0",
                                             "sph.blocks[0].region.max.z=0.1"};
  Outcome o;
  ASSERT_NO_THROW(o = strike(on_floor, 0.1, 3.0, 0.03, 0.06, 0.95));
  EXPECT_TRUE(o.finite);
  EXPECT_GT(o.substepped, 0u);
  std::printf("crushed cube: %llu windows, %llu sub-stepped, at most %u sub-steps; energy error %.3e\n",
              static_cast<unsigned long long>(o.windows), static_cast<unsigned long long>(o.substepped),
              o.most_substeps, o.energy_error);
  EXPECT_LT(o.energy_error, 0.01);
}

}  // namespace
