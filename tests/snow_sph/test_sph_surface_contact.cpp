// Particle-surface penalty contact (snow_sph/surface_contact.hpp) against hand
// calculations: penalty force, its split over the facet nodes, Coulomb friction
// with its elastic stick (carried between calls), damping, momentum balance, concave corners, edges,
// the deepest penetration, and independence of the thread count.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <omp.h>

#include "snow_sph/surface_contact.hpp"

namespace {

using snow_sph::ContactSurface;
using snow_sph::SurfaceContactParameters;
using snow_sph::SurfaceContactResult;

constexpr double kRadius = 0.005, kStiffness = 1e5, kMass = 1e-3, kDt = 1e-6;

// Adds a quad with corners (x0, y0)-(x1, y1) at height z, outward normal -z
// (the underside of a tyre: the terrain is below it).
void add_flat_quad(ContactSurface& s, double x0, double y0, double x1, double y1, double z, double mu) {
  const auto base = static_cast<std::uint32_t>(s.x.size());
  const double xs[4] = {x0, x0, x1, x1}, ys[4] = {y0, y1, y1, y0};
  for (int a = 0; a < 4; ++a) {
    s.x.push_back(xs[a]), s.y.push_back(ys[a]), s.z.push_back(z);
    s.vx.push_back(0), s.vy.push_back(0), s.vz.push_back(0);
  }
  // (x2 - x0) x (x3 - x1) = (d, d, 0) x (d, -d, 0) = -2 d^2 e_z: outward -z.
  for (std::uint32_t a = 0; a < 4; ++a) s.facet_nodes.push_back(base + a);
  s.friction_coefficient.push_back(mu);
}

SurfaceContactParameters params() {
  SurfaceContactParameters p;
  p.particle_radius_m = kRadius;
  p.stiffness_N_per_m = kStiffness;
  return p;
}

struct Particle {
  double x, y, z, vx = 0, vy = 0, vz = 0, m = kMass;
  double ax = 0, ay = 0, az = 0;
};

SurfaceContactResult contact(const ContactSurface& s, Particle& p, const SurfaceContactParameters& prm = params()) {
  SurfaceContactResult loads;
  snow_sph::surface_contact(s, prm, 1, &p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.m, kDt, &p.ax, &p.ay, &p.az, loads);
  return loads;
}

TEST(SurfaceContact, PenaltyForceOnAParticleBelowAFacetCentreIsSplitEquallyOverItsNodes) {
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.3);
  const double delta = 0.001;
  Particle p{0.0, 0.0, -(kRadius - delta)};
  const SurfaceContactResult l = contact(s, p);
  EXPECT_NEAR(p.az * kMass, -kStiffness * delta, 1e-9);  // pushed away from the tyre (down)
  EXPECT_NEAR(p.ax, 0.0, 1e-12);
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(l.node_fz[a], kStiffness * delta / 4.0, 1e-9);
  EXPECT_NEAR(l.facet_normal_force_N[0], kStiffness * delta, 1e-9);
  // One particle touches the (2 r)^2 = 1e-4 m^2 of the 4e-4 m^2 facet it stands for.
  EXPECT_NEAR(l.facet_contact_area_m2[0], 1e-4, 1e-15);
  EXPECT_NEAR(l.facet_pressure_Pa[0], kStiffness * delta / 1e-4, 1e-6);
  EXPECT_EQ(l.particles_in_contact[0], 1u);
  EXPECT_NEAR(l.elastic_energy_J, 0.5 * kStiffness * delta * delta, 1e-15);
}

// The contact area is the touched part of a facet: a lattice of particles at
// spacing 2 r under a facet covers it in (2 r)^2 patches, so a facet of 10 x 10
// patches under a 4 x 4 block of particles touches 16 patches (16 %), the whole
// facet under a 10 x 10 block, and never more than the facet under a denser one.
TEST(SurfaceContact, TheContactAreaIsTheTouchedPartOfTheFacet) {
  ContactSurface s;
  const double d = 2.0 * kRadius, side = 10 * d;
  add_flat_quad(s, 0.0, 0.0, side, side, 0.0, 0.3);
  auto touched = [&](int per_side, double spacing) {
    std::vector<double> x, y, z, vx, vy, vz, m, ax, ay, az;
    for (int i = 0; i < per_side; ++i)
      for (int j = 0; j < per_side; ++j) {
        x.push_back((i + 0.5) * spacing), y.push_back((j + 0.5) * spacing), z.push_back(-0.9 * kRadius);
        vx.push_back(0), vy.push_back(0), vz.push_back(0), m.push_back(kMass), ax.push_back(0), ay.push_back(0),
            az.push_back(0);
      }
    SurfaceContactResult loads;
    snow_sph::surface_contact(s, params(), x.size(), x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data(),
                              m.data(), kDt, ax.data(), ay.data(), az.data(), loads);
    return loads;
  };
  const SurfaceContactResult part = touched(4, d);
  EXPECT_NEAR(part.facet_contact_area_m2[0], 16 * d * d, 1e-15);
  EXPECT_NEAR(part.facet_pressure_Pa[0], part.facet_normal_force_N[0] / (16 * d * d), 1e-6);
  EXPECT_NEAR(touched(10, d).facet_contact_area_m2[0], side * side, 1e-15);
  EXPECT_NEAR(touched(15, side / 15).facet_contact_area_m2[0], side * side, 1e-15);
}

TEST(SurfaceContact, NoForceBeyondTheRadiusOrBeyondTheDepthBehindTheFacet) {
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.3);
  Particle far{0.0, 0.0, -1.001 * kRadius};
  EXPECT_EQ(contact(s, far).particles_in_contact[0], 0u);
  EXPECT_EQ(far.az, 0.0);
  Particle behind{0.0, 0.0, 2.01 * kRadius};  // default max depth: one diameter
  EXPECT_EQ(contact(s, behind).particles_in_contact[0], 0u);
}

TEST(SurfaceContact, DampingActsOnlyWhileApproaching) {
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.0);
  const double delta = 0.001, c = 2.0 * 0.2 * std::sqrt(kStiffness * kMass);
  Particle in{0.0, 0.0, -(kRadius - delta)};
  in.vz = 0.3;  // moving up, into the tyre
  contact(s, in);
  EXPECT_NEAR(in.az * kMass, -(kStiffness * delta + c * 0.3), 1e-9);
  Particle out{0.0, 0.0, -(kRadius - delta)};
  out.vz = -0.3;  // leaving
  contact(s, out);
  EXPECT_NEAR(out.az * kMass, -kStiffness * delta, 1e-9);
}

TEST(SurfaceContact, SlidingLoadsTheStickSpringUpToCoulombThenDissipatesMuFnPerSlip) {
  ContactSurface s;
  const double mu = 0.3, delta = 0.001, v = 2.0;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, mu);
  const double fn = kStiffness * delta, c_t = 2.0 * 0.2 * std::sqrt(kStiffness * kMass);
  snow_sph::FrictionHistory history;
  auto call = [&](double vx) {
    Particle p{0.0, 0.0, -(kRadius - delta)};
    p.vx = vx;
    SurfaceContactResult l;
    snow_sph::surface_contact(s, params(), 1, &p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.m, kDt, &p.ax, &p.ay,
                              &p.az, l, &history);
    return std::make_pair(p, l);
  };
  // First step from an unloaded spring: k_t v dt plus the damper c_t v.
  auto [first, l1] = call(v);
  EXPECT_NEAR(first.ax * kMass, -(kStiffness * v * kDt + c_t * v), 1e-9);
  // The spring grows by k_t v dt = 0.2 N per step: spring plus damper at step 100.
  for (int step = 2; step < 100; ++step) call(v);
  auto [before, l100] = call(v);
  EXPECT_NEAR(before.ax * kMass, -(100 * kStiffness * v * kDt + c_t * v), 1e-9);
  // The spring alone reaches mu fn = 30 N at step 150; from then on it slides.
  for (int step = 101; step <= 200; ++step) call(v);
  auto [slide, l] = call(v);
  EXPECT_NEAR(slide.ax * kMass, -mu * fn, 1e-9);
  EXPECT_NEAR(l.facet_tangential_x_N[0], mu * fn, 1e-9);  // the surface is dragged along
  EXPECT_NEAR(l.friction_dissipation_J, mu * fn * v * kDt, 1e-12 * mu * fn * v * kDt);
  // Reversing: the spring unloads through zero before sliding the other way.
  auto [back, lb] = call(-v);
  EXPECT_NEAR(back.ax * kMass, -(mu * fn - kStiffness * v * kDt) + c_t * v, 1e-9);
  // Without friction nothing is stored.
  ContactSurface smooth = s;
  smooth.friction_coefficient[0] = 0.0;
  snow_sph::FrictionHistory none;
  Particle free{0.0, 0.0, -(kRadius - delta)};
  free.vx = v;
  SurfaceContactResult lf;
  snow_sph::surface_contact(smooth, params(), 1, &free.x, &free.y, &free.z, &free.vx, &free.vy, &free.vz, &free.m,
                            kDt, &free.ax, &free.ay, &free.az, lf, &none);
  EXPECT_EQ(free.ax, 0.0);
  ASSERT_EQ(none.sticks.size(), 1u);
  EXPECT_EQ(none.sticks[0].force[0], 0.0);
}

// A particle pressed against a facet and pulled along it: below mu fn it comes
// to rest at the spring's elastic offset F / k_t (no creep); above, it slides
// with acceleration (F - mu fn) / m. Central difference, as the solver steps.
TEST(SurfaceContact, ASteadyPullBelowCoulombSticksAtTheElasticOffsetWithoutCreep) {
  ContactSurface s;
  const double mu = 0.3, delta = 0.001;
  add_flat_quad(s, -0.5, -0.5, 0.5, 0.5, 0.0, mu);  // long enough for 2 ms of sliding (0.06 m)
  const double fn = kStiffness * delta;
  auto pull = [&](double force, int steps) {
    snow_sph::FrictionHistory history;
    Particle p{0.0, 0.0, -(kRadius - delta)};
    for (int step = 0; step < steps; ++step) {
      p.ax = force / kMass, p.ay = 0.0, p.az = 0.0;
      SurfaceContactResult l;
      snow_sph::surface_contact(s, params(), 1, &p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.m, kDt, &p.ax, &p.ay,
                                &p.az, l, &history);
      p.az = 0.0;  // hold the depth: this test is about the tangential direction
      p.vx += p.ax * kDt;
      p.x += p.vx * kDt;
    }
    return p;
  };
  // Held: 6000 steps are 12 decay times 1 / (zeta omega) of the stick spring.
  // (The damper m / (20 dt) used before would creep here at F / c = 0.3 m/s.)
  const double f_stick = 0.5 * mu * fn;
  const Particle held = pull(f_stick, 6000);
  EXPECT_NEAR(held.x, f_stick / kStiffness, 1e-3 * f_stick / kStiffness);
  EXPECT_LT(std::fabs(held.vx), 1e-4);
  // Pulled with twice the friction it slides: between 1 ms and 2 ms the
  // friction is exactly mu fn, so the speed grows by (F - mu fn) / m per second.
  const double f_slide = 2.0 * mu * fn;
  const double v1 = pull(f_slide, 1000).vx, v2 = pull(f_slide, 2000).vx;
  const double dv = (f_slide - mu * fn) / kMass * 1000 * kDt;
  EXPECT_NEAR(v2 - v1, dv, 1e-9 * dv);
}

TEST(SurfaceContact, TheStickFollowsTheParticleOntoANeighbouringFacetAndThroughARenumbering) {
  ContactSurface s;
  const double mu = 0.3, delta = 0.001;
  add_flat_quad(s, -0.02, -0.01, 0.0, 0.01, 0.0, mu);  // facet A (id 10)
  add_flat_quad(s, 0.0, -0.01, 0.02, 0.01, 0.0, mu);   // facet B (id 11), coplanar
  s.facet_id = {10, 11};
  snow_sph::FrictionHistory history;
  Particle p{-0.005, 0.0, -(kRadius - delta)};
  p.vx = 0.5;
  for (int step = 0; step < 50; ++step) {
    p.ax = 0.0;
    SurfaceContactResult l;
    snow_sph::surface_contact(s, params(), 1, &p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.m, kDt, &p.ax, &p.ay,
                              &p.az, l, &history);
  }
  const double loaded = p.ax;
  ASSERT_LT(loaded * kMass, -0.5 * kStiffness * 50 * 0.5 * kDt);
  // Same motion on facet B: the spring carries over (one more step's load).
  auto next_on = [&](const ContactSurface& surface, double x) {
    snow_sph::FrictionHistory h = history;
    Particle q{x, 0.0, -(kRadius - delta)};
    q.vx = 0.5;
    SurfaceContactResult l;
    snow_sph::surface_contact(surface, params(), 1, &q.x, &q.y, &q.z, &q.vx, &q.vy, &q.vz, &q.m, kDt, &q.ax, &q.ay,
                              &q.az, l, &h);
    return q.ax;
  };
  const double expected = loaded - kStiffness * 0.5 * kDt / kMass;
  EXPECT_NEAR(next_on(s, 0.005), expected, 1e-9 * std::fabs(expected));
  // The owner sends the facets in another order: the id keeps the stick.
  ContactSurface swapped;
  add_flat_quad(swapped, 0.0, -0.01, 0.02, 0.01, 0.0, mu);
  add_flat_quad(swapped, -0.02, -0.01, 0.0, 0.01, 0.0, mu);
  swapped.facet_id = {11, 10};
  EXPECT_NEAR(next_on(swapped, -0.005), expected, 1e-9 * std::fabs(expected));
  // A facet at 90 degrees (a groove wall) does not inherit it: it starts unloaded.
  ContactSurface wall;
  const auto base = static_cast<std::uint32_t>(wall.x.size());
  const double ys[4] = {-0.01, 0.01, 0.01, -0.01}, zs[4] = {-0.01, -0.01, 0.01, 0.01};
  for (int a = 0; a < 4; ++a) {
    wall.x.push_back(0.0), wall.y.push_back(ys[a]), wall.z.push_back(zs[a]);
    wall.vx.push_back(0), wall.vy.push_back(0), wall.vz.push_back(0);
  }
  for (std::uint32_t a = 0; a < 4; ++a) wall.facet_nodes.push_back(base + a);
  wall.friction_coefficient.push_back(mu);
  wall.facet_id = {12};
  snow_sph::FrictionHistory h = history;
  Particle q{-(kRadius - delta), 0.0, 0.0};  // the wall's outward normal is -x
  q.vz = 0.5;
  SurfaceContactResult l;
  snow_sph::surface_contact(wall, params(), 1, &q.x, &q.y, &q.z, &q.vx, &q.vy, &q.vz, &q.m, kDt, &q.ax, &q.ay, &q.az,
                            l, &h);
  const double c_t = 2.0 * 0.2 * std::sqrt(kStiffness * kMass);
  EXPECT_NEAR(q.az * kMass, -(kStiffness * 0.5 * kDt + c_t * 0.5), 1e-9);
}

TEST(SurfaceContact, OverASharedEdgeOfCoplanarFacetsTheForceIsOneFacetsWorth) {
  ContactSurface s;
  add_flat_quad(s, -0.02, -0.01, 0.0, 0.01, 0.0, 0.3);
  add_flat_quad(s, 0.0, -0.01, 0.02, 0.01, 0.0, 0.3);
  const double delta = 0.001;
  Particle centre{-0.01, 0.0, -(kRadius - delta)};
  contact(s, centre);
  for (double x : {1e-9, 0.0}) {  // just off the shared edge, and exactly on it
    Particle edge{x, 0.0, -(kRadius - delta)};
    const SurfaceContactResult l = contact(s, edge);
    EXPECT_NEAR(edge.az, centre.az, 1e-9 * std::fabs(centre.az)) << x;
    EXPECT_NEAR(l.total_fz_N, kStiffness * delta, 1e-9) << x;
  }
}

TEST(SurfaceContact, InAConcaveCornerBothFacesPushAndTheForceIsTheirSum) {
  // Floor z = 0 (normal -z) and a wall x = 0 (normal +x) meeting at a concave corner.
  ContactSurface s;
  add_flat_quad(s, 0.0, -0.01, 0.02, 0.01, 0.0, 0.0);
  const auto base = static_cast<std::uint32_t>(s.x.size());
  const double wx[4] = {0, 0, 0, 0}, wy[4] = {-0.01, -0.01, 0.01, 0.01}, wz[4] = {0, -0.02, -0.02, 0};
  for (int a = 0; a < 4; ++a) {
    s.x.push_back(wx[a]), s.y.push_back(wy[a]), s.z.push_back(wz[a]);
    s.vx.push_back(0), s.vy.push_back(0), s.vz.push_back(0);
  }
  // (x2 - x0) x (x3 - x1) = (0, 0.02, -0.02) x (0, 0.02, 0.02) = (0.0008, 0, 0): +x.
  for (std::uint32_t a = 0; a < 4; ++a) s.facet_nodes.push_back(base + a);
  s.friction_coefficient.push_back(0.0);
  const double dx = 0.001, dz = 0.002;
  Particle p{kRadius - dx, 0.0, -(kRadius - dz)};
  const SurfaceContactResult l = contact(s, p);
  EXPECT_NEAR(p.ax * kMass, kStiffness * dx, 1e-9);
  EXPECT_NEAR(p.az * kMass, -kStiffness * dz, 1e-9);
  EXPECT_EQ(l.particles_in_contact[0] + l.particles_in_contact[1], 2u);
}

TEST(SurfaceContact, AConvexEdgePushesAlongTheLineFromTheEdge) {
  // One facet; the particle beyond its edge x = 0.01, below and outside.
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.0);
  const double d = 0.6 * kRadius;
  Particle p{0.01 + d / std::sqrt(2.0), 0.0, -d / std::sqrt(2.0)};
  contact(s, p);
  const double f = kStiffness * (kRadius - d);
  EXPECT_NEAR(p.ax * kMass, f / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(p.az * kMass, -f / std::sqrt(2.0), 1e-9);
}

// The facet's pressure part is the force along that line too, not the normal
// force times the facet's normal (which would put all of it in -z): at a block's
// edge that is where the groove force and the motion resistance act.
TEST(SurfaceContact, AnEdgeContactsPressurePartIsAlongTheLineFromTheEdge) {
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.0);
  const double d = 0.6 * kRadius;
  Particle p{0.01 + d / std::sqrt(2.0), 0.0, -d / std::sqrt(2.0)};
  const SurfaceContactResult l = contact(s, p);
  const double f = kStiffness * (kRadius - d);
  // On the surface: the reaction, -f along the line from the edge to the particle
  // (to the closest point's rounding, as the force on the particle above).
  EXPECT_NEAR(l.facet_pressure_x_N[0], -f / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(l.facet_pressure_y_N[0], 0.0, 1e-9);
  EXPECT_NEAR(l.facet_pressure_z_N[0], f / std::sqrt(2.0), 1e-9);
}

// A sipe is a zero-width slit (tyre_fe/revolve.cpp): two coincident faces at
// x = 0 reaching 8 mm into the tread from its top (z = 0, the terrain below).
// A particle 1 mm inside the rubber, 2 mm to the side of the slit, is in front
// of one face (gap 2 mm) and behind the other (2 mm): both would push it, the
// slit's faces apart with k r and k (r - 2 mm) and the particle towards the
// slit. It meets the rubber through the tread top only, which pushes it along
// -z with the force of a radius's penetration (the cap of a particle past the
// facet plane); the faces carry nothing. Exact arithmetic but for the
// bilinear weights' rounding, hence 1e-9 N on forces of 500 N.
TEST(SurfaceContact, AClosedSlitsFacesTakeNoParticle) {
  ContactSurface s;
  add_flat_quad(s, -0.02, -0.01, 0.0, 0.01, 0.0, 0.0);  // the tread top either side of the slit
  add_flat_quad(s, 0.0, -0.01, 0.02, 0.01, 0.0, 0.0);
  auto add_slit_face = [&](double outward_x) {
    const auto base = static_cast<std::uint32_t>(s.x.size());
    const double ys[4] = {-0.01, -0.01, 0.01, 0.01}, zs[4] = {0.0, 0.008, 0.008, 0.0};
    for (int a = 0; a < 4; ++a) {
      const int k = outward_x > 0 ? a : 3 - a;  // reversed order, reversed normal
      s.x.push_back(0.0), s.y.push_back(ys[k]), s.z.push_back(zs[k]);
      s.vx.push_back(0), s.vy.push_back(0), s.vz.push_back(0);
    }
    for (std::uint32_t a = 0; a < 4; ++a) s.facet_nodes.push_back(base + a);
    s.friction_coefficient.push_back(0.0);
  };
  add_slit_face(+1.0);  // the face of the block on x < 0
  add_slit_face(-1.0);  // the face of the block on x > 0
  Particle open{0.002, 0.0, 0.001};
  const SurfaceContactResult without_rule = contact(s, open);
  ASSERT_GT(without_rule.particles_in_contact[2] + without_rule.particles_in_contact[3], 0u)
      << "the slit's faces must be within reach of the particle for the test to mean anything";
  EXPECT_GT(std::fabs(open.ax * kMass), 0.1 * kStiffness * kRadius);

  s.closed_slit = {0, 0, 1, 1};
  Particle p{0.002, 0.0, 0.001};
  const SurfaceContactResult l = contact(s, p);
  EXPECT_NEAR(p.ax * kMass, 0.0, 1e-9);
  EXPECT_NEAR(p.az * kMass, -kStiffness * kRadius, 1e-9);
  EXPECT_EQ(l.particles_in_contact[2] + l.particles_in_contact[3], 0u);
  EXPECT_NEAR(l.total_fz_N, kStiffness * kRadius, 1e-9);
}

// The deepest penetration is radius - d for the particle centre's signed
// distance d to the facet (or to the edge). The heights are exact here and the
// facet's normal is exactly -z, so the only error is the rounding of radius - d:
// 1e-15 m is far above it (~1e-18 m) and far below any overlap of interest.
constexpr double kOverlapRounding = 1e-15;

TEST(SurfaceContact, MaxPenetrationIsTheOverlapOfTheParticlesSphereWithTheFacet) {
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.3);
  Particle p{0.002, -0.003, -(kRadius - 0.0013)};  // centre 3.7 mm below the facet, radius 5 mm
  EXPECT_NEAR(contact(s, p).max_penetration_m, 0.0013, kOverlapRounding);
  EXPECT_EQ(contact(s, p).particles_behind_surface, 0u);  // in contact, its centre in front
  Particle apart{0.0, 0.0, -1.001 * kRadius};
  EXPECT_EQ(contact(s, apart).max_penetration_m, 0.0);
}

TEST(SurfaceContact, MaxPenetrationBeyondTheRadiusWhenTheCentreCrossedTheFacet) {
  // The centre 0.3 radius behind the facet: the overlap is 1.3 radii, while
  // the force stays that of one radius.
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.3);
  Particle p{0.0, 0.0, 0.3 * kRadius};
  const SurfaceContactResult l = contact(s, p);
  EXPECT_NEAR(l.max_penetration_m, 1.3 * kRadius, kOverlapRounding);
  EXPECT_NEAR(p.az * kMass, -kStiffness * kRadius, 1e-9);
  EXPECT_EQ(l.particles_behind_surface, 1u);  // its centre is behind the facet
}

TEST(SurfaceContact, MaxPenetrationAtAnEdgeIsTheRadiusLessTheDistanceToTheEdge) {
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.0);
  Particle p{0.01 + 0.003, 0.0, -0.002};  // 3 mm beyond the edge x = 0.01, 2 mm below
  EXPECT_NEAR(contact(s, p).max_penetration_m, kRadius - std::sqrt(13e-6), kOverlapRounding);
}

TEST(SurfaceContact, MaxPenetrationIsTheDeepestOfSeveralParticles) {
  ContactSurface s;
  add_flat_quad(s, -0.01, -0.01, 0.01, 0.01, 0.0, 0.3);
  const double x[3] = {-0.005, 0.0, 0.005}, y[3] = {0, 0, 0}, z[3] = {-0.004, -0.0025, -0.0045};
  const double v[3] = {0, 0, 0}, m[3] = {kMass, kMass, kMass};
  double ax[3] = {0, 0, 0}, ay[3] = {0, 0, 0}, az[3] = {0, 0, 0};
  SurfaceContactResult l;
  snow_sph::surface_contact(s, params(), 3, x, y, z, v, v, v, m, kDt, ax, ay, az, l);
  EXPECT_NEAR(l.max_penetration_m, kRadius - 0.0025, kOverlapRounding);
  // ... and where it is: the middle particle, on the one facet.
  EXPECT_EQ(l.deepest_x_m, 0.0);
  EXPECT_EQ(l.deepest_z_m, -0.0025);
  EXPECT_EQ(l.deepest_facet, 0);
}

// A patch of a cylinder (radius 0.35 m, axis y) seen from below, moving, and
// particles scattered under it with random velocities.
struct Scatter {
  ContactSurface s;
  std::vector<double> x, y, z, vx, vy, vz, m;
};
Scatter scattered() {
  Scatter c;
  const int nt = 6, ny = 6;
  const double r = 0.35;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nt; ++i) {
      const double th = -0.15 + 0.3 * i / nt, yy = -0.05 + 0.1 * j / ny;
      c.s.x.push_back(r * std::sin(th)), c.s.y.push_back(yy), c.s.z.push_back(r - r * std::cos(th));
      c.s.vx.push_back(1.0 + 0.1 * th), c.s.vy.push_back(0.01 * yy), c.s.vz.push_back(-0.2);
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nt + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nt; ++i) {
      // Outward (away from the axis, down at the bottom): order (i,j), (i,j+1), (i+1,j+1), (i+1,j).
      for (auto n : {id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)}) c.s.facet_nodes.push_back(n);
      c.s.friction_coefficient.push_back(0.3 + 0.05 * (i % 3));
    }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 3000; ++k) {
    const double th = -0.15 + 0.3 * u(rng), yy = -0.05 + 0.1 * u(rng), rr = r + (u(rng) - 0.7) * 2.5 * kRadius;
    c.x.push_back(rr * std::sin(th)), c.y.push_back(yy), c.z.push_back(r - rr * std::cos(th));
    c.vx.push_back(u(rng) - 0.5), c.vy.push_back(u(rng) - 0.5), c.vz.push_back(u(rng) - 0.5);
    c.m.push_back(kMass * (0.5 + u(rng)));
  }
  return c;
}

TEST(SurfaceContact, MomentumIsExchangedExactlyAndFacetSumsMatchNodeSums) {
  Scatter c = scattered();
  const std::size_t n = c.x.size();
  std::vector<double> ax(n, 0.0), ay(n, 0.0), az(n, 0.0);
  SurfaceContactResult l;
  snow_sph::surface_contact(c.s, params(), n, c.x.data(), c.y.data(), c.z.data(), c.vx.data(), c.vy.data(),
                            c.vz.data(), c.m.data(), kDt, ax.data(), ay.data(), az.data(), l);
  double px = 0, py = 0, pz = 0, nx = 0, ny = 0, nz = 0;
  std::uint32_t in_contact = 0;
  for (std::size_t i = 0; i < n; ++i) px += c.m[i] * ax[i], py += c.m[i] * ay[i], pz += c.m[i] * az[i];
  for (std::size_t a = 0; a < l.node_fx.size(); ++a) nx += l.node_fx[a], ny += l.node_fy[a], nz += l.node_fz[a];
  for (auto k : l.particles_in_contact) in_contact += k;
  ASSERT_GT(in_contact, 500u);
  const double scale = std::fabs(pz);
  EXPECT_NEAR(px, -nx, 1e-12 * scale);
  EXPECT_NEAR(py, -ny, 1e-12 * scale);
  EXPECT_NEAR(pz, -nz, 1e-12 * scale);
  EXPECT_NEAR(nx, l.total_fx_N, 1e-12 * scale);
  EXPECT_NEAR(nz, l.total_fz_N, 1e-12 * scale);
  EXPECT_GT(nz, 0.0);  // the particles push the tyre up
  // The facets' pressure and friction parts add up to the same force (faces, edges
  // and corners of the scattered surface alike), to the rounding of ~1000 terms.
  double fx = 0, fy = 0, fz = 0;
  for (std::size_t f = 0; f < l.facet_pressure_x_N.size(); ++f) {
    fx += l.facet_pressure_x_N[f] + l.facet_tangential_x_N[f];
    fy += l.facet_pressure_y_N[f] + l.facet_tangential_y_N[f];
    fz += l.facet_pressure_z_N[f] + l.facet_tangential_z_N[f];
  }
  EXPECT_NEAR(fx, nx, 1e-12 * scale);
  EXPECT_NEAR(fy, ny, 1e-12 * scale);
  EXPECT_NEAR(fz, nz, 1e-12 * scale);
}

TEST(SurfaceContact, ResultDoesNotDependOnTheThreadCount) {
  Scatter c = scattered();
  const std::size_t n = c.x.size();
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    std::vector<double> a(3 * n, 0.0);
    SurfaceContactResult l;
    snow_sph::FrictionHistory history;
    for (int call = 0; call < 3; ++call) {  // the last call uses the sticks of the others
      std::fill(a.begin(), a.end(), 0.0);
      snow_sph::surface_contact(c.s, params(), n, c.x.data(), c.y.data(), c.z.data(), c.vx.data(), c.vy.data(),
                                c.vz.data(), c.m.data(), kDt, a.data(), a.data() + n, a.data() + 2 * n, l, &history);
    }
    a.insert(a.end(), l.node_fx.begin(), l.node_fx.end());
    a.insert(a.end(), l.node_fz.begin(), l.node_fz.end());
    a.insert(a.end(), l.facet_normal_force_N.begin(), l.facet_normal_force_N.end());
    a.push_back(l.max_penetration_m);
    return a;
  };
  const auto one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k], two[k]) << k;
}

TEST(SurfaceContact, StableStepOfThePenaltySpring) {
  EXPECT_DOUBLE_EQ(snow_sph::surface_contact_stable_dt(1e-3, 1e5), 2.0 * std::sqrt(1e-8));
}

}  // namespace
