// The active terrain domain's wake limit (snow_sph/solver.hpp, set_active_domain):
// a particle still moving stays active beyond the margin only up to the wake
// limit; farther away it is set at rest. The wake of a tyre on water keeps moving
// over the frictionless floor and, without the limit, stays active back to the start.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>

#include "snow_sph/boundaries.hpp"
#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"
#include "test_support.hpp"

namespace {

const std::string kScene = test_support::source_dir() + "/tests/snow_sph/test_sph_substeps.textproto";

// A 5 x 5 x 5 cube of particles (centres 0.46 ... 0.54 m) all moving at 1 m/s
// along x, and a coupled surface far above it (no contact) whose box ends at
// x = 0.42 m. Returns each particle's speed after the domain is first drawn.
struct Drawn {
  std::vector<double> x, speed;
  std::vector<int> active;
};
struct Terrain {
  snow_sph::Model model;
  snow_sph::Solver solver;
  explicit Terrain(snow_sph::Model m) : model(std::move(m)), solver(model) {}
};
std::unique_ptr<Terrain> drawn_terrain(double margin_m, double wake_limit_m) {
  const auto loaded = snow_sph::load_sph_scene(kScene, {});
  auto t = std::make_unique<Terrain>(snow_sph::build_model(loaded->message));
  snow_sph::Model& model = t->model;
  snow_sph::Solver& solver = t->solver;
  snow_sph::SurfaceContactParameters contact;
  contact.particle_radius_m = 0.5 * model.settings.spacing;
  contact.stiffness_N_per_m = model.settings.contact_stiffness;
  solver.couple(contact);
  solver.set_active_domain(margin_m, 0.01, wake_limit_m);
  snow_sph::Particles& p = model.particles;
  for (std::size_t i = 0; i < p.n_real; ++i) p.vx[i] = 1.0;
  snow_sph::ContactSurface s;
  const double xs[4] = {0.40, 0.40, 0.42, 0.42}, ys[4] = {0.40, 0.60, 0.60, 0.40};
  for (int a = 0; a < 4; ++a) {
    s.x.push_back(xs[a]), s.y.push_back(ys[a]), s.z.push_back(0.9);
    s.vx.push_back(0.0), s.vy.push_back(0.0), s.vz.push_back(0.0);
  }
  s.facet_nodes = {0, 1, 2, 3};
  s.friction_coefficient = {0.3};
  solver.prepare();
  solver.contact_surface(&s, 0);
  solver.initialise();
  return t;
}
Drawn draw_domain(double margin_m, double wake_limit_m) {
  const auto t = drawn_terrain(margin_m, wake_limit_m);
  const snow_sph::Particles& p = t->model.particles;
  Drawn d;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    d.x.push_back(p.x[i]);
    d.speed.push_back(std::hypot(p.vx[i], std::hypot(p.vy[i], p.vz[i])));
    d.active.push_back(p.active[i]);
  }
  return d;
}

TEST(ActiveDomain, MovingParticlesStayActiveUpToTheWakeLimitAndNoFarther) {
  const double margin = 0.02, limit = 0.07, box_end = 0.42;
  const Drawn without = draw_domain(margin, 0.0);
  const Drawn with = draw_domain(margin, limit);
  ASSERT_EQ(with.x.size(), 125u);
  int kept = 0;
  for (std::size_t i = 0; i < with.x.size(); ++i) {
    // Without a limit every moving particle stays active and keeps its speed.
    EXPECT_EQ(without.active[i], 1) << i;
    EXPECT_DOUBLE_EQ(without.speed[i], 1.0) << i;
    // With it, those within the limit of the box's end (x <= 0.49 m) stay, the others rest.
    const bool near = with.x[i] <= box_end + limit;
    EXPECT_EQ(with.active[i], near ? 1 : 0) << "x = " << with.x[i];
    EXPECT_DOUBLE_EQ(with.speed[i], near ? 1.0 : 0.0) << "x = " << with.x[i];
    kept += near;
  }
  EXPECT_EQ(kept, 50);  // the two planes of particles at x = 0.46 and 0.48 m
}

// A particle set at rest outside the domain is not integrated, so its
// acceleration (that of its last active step) does not limit the terrain's step:
// the limit is the same with 1e12 m/s^2 on every resting particle, and is set by
// it once the particle is active again. 1e12 m/s^2 gives sqrt(h / a) of a few
// microseconds, far below the cube's Courant limit, so the check can fail.
TEST(ActiveDomain, AParticleAtRestOutsideTheDomainDoesNotLimitTheStep) {
  auto t = drawn_terrain(0.02, 0.07);
  snow_sph::Particles& p = t->model.particles;
  const double before = t->solver.stability_limit_dt();
  std::size_t resting = p.n_real;
  for (std::size_t i = 0; i < p.n_real; ++i)
    if (!p.active[i]) p.ax[i] = 1e12, resting = i;
  ASSERT_LT(resting, p.n_real);
  EXPECT_EQ(t->solver.stability_limit_dt(), before);
  p.active[resting] = 1;
  EXPECT_LT(t->solver.stability_limit_dt(), 0.01 * before);
}

// The wall's push (wall_repulsion) acts on particles in the domain only: a
// resting particle gets no force pass that would reset its acceleration, so a
// push added every step would pile up on it without bound. One resting and one
// active particle are put a quarter spacing inside the box's floor: the active
// one is pushed up, the resting one gets nothing and the wall does no work on it.
TEST(ActiveDomain, TheWallPushesOnlyParticlesInTheDomain) {
  auto t = drawn_terrain(0.02, 0.07);
  snow_sph::Model& model = t->model;
  snow_sph::Particles& p = model.particles;
  std::size_t resting = p.n_real, active = p.n_real;
  for (std::size_t i = 0; i < p.n_real; ++i) (p.active[i] ? active : resting) = i;
  ASSERT_LT(resting, p.n_real);
  ASSERT_LT(active, p.n_real);
  const snow_sph::MirrorPlane* floor = nullptr;
  for (const auto& plane : model.planes)
    if (plane.axis == 2 && plane.inside_sign > 0 && !plane.symmetry) floor = &plane;
  ASSERT_NE(floor, nullptr);
  for (std::size_t i : {resting, active}) p.z[i] = floor->position + 0.25 * model.settings.spacing;
  std::vector<double> ax(p.n_real, 0.0), ay(p.n_real, 0.0), az(p.n_real, 0.0), power(p.n_real, 1.0);
  snow_sph::wall_repulsion(model, ax.data(), ay.data(), az.data(), power.data());
  EXPECT_GT(az[active], 0.0);
  EXPECT_EQ(az[resting], 0.0);
  EXPECT_EQ(power[resting], 0.0);
}

}  // namespace
