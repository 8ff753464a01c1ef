// The shared penalty contact law (common/include/cosim/penalty_contact.hpp)
// against closed forms: the coefficient of restitution of a damped penalty
// impact for each damping choice, the energy a Coulomb spring-slider
// dissipates, and the stopping distance of a block braked by Coulomb friction.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/penalty_contact.hpp"

namespace {

using namespace cosim::penalty;

constexpr double kPi = 3.14159265358979323846;

// A particle of mass m falls at v0 onto a rigid plane (normal +z, depth = -z)
// and is integrated through the contact with symplectic Euler at dt = 1e-5 of
// 1 / omega_n. Returns the speed it leaves with over v0.
double restitution(double zeta, Damping damping) {
  const double k = 1.0e4, m = 0.01, v0 = 1.0;
  const double omega = std::sqrt(k / m), dt = 1.0e-5 / omega;
  const double c = damping_coefficient(zeta, k, m);
  double z = 0.0, v = -v0;
  for (long step = 0; step < 10000000; ++step) {
    const double depth = -z;
    const double f = depth > 0.0 ? normal_force(k, depth, v, c, damping).force_N : 0.0;
    v += f / m * dt;
    z += v * dt;
    if (z > 0.0 && v > 0.0) return v / v0;
  }
  return -1.0;
}

// Closed forms, derived from the damped oscillator x = v0/wd e^(-zeta wn t) sin(wd t):
// approach only: the particle stops at wd t = acos(zeta), depth v0/wn e^(-zeta acos(zeta)/s),
// and the undamped spring gives it back at wn times that depth;
// both ways: the force k x + c x' reaches zero at wd t = pi - atan(2 zeta s / (1 - 2 zeta^2))
// with speed v0 e^(-zeta wn t) (Schwager and Poeschel, Granular Matter 9, 2007, 465).
double approach_only_closed_form(double zeta) {
  const double s = std::sqrt(1.0 - zeta * zeta);
  return std::exp(-zeta * std::acos(zeta) / s);
}
double both_ways_closed_form(double zeta) {
  const double s = std::sqrt(1.0 - zeta * zeta);
  return std::exp(-zeta / s * (kPi - std::atan(2.0 * zeta * s / (1.0 - 2.0 * zeta * zeta))));
}

// Tolerance: symplectic Euler is first order, so the restitution is off by
// O(omega dt) = 1e-5, and the contact's start and end are found within one step
// (another 1e-5 of a radian); 1e-4 is ten times that and far below the
// differences between the damping choices (0.05-0.5 here).
constexpr double kRestitutionTolerance = 1e-4;

TEST(PenaltyContact, RestitutionWithDampingOnApproachOnly) {
  for (double zeta : {0.05, 0.1, 0.2, 0.5})
    EXPECT_NEAR(restitution(zeta, Damping::approach_only), approach_only_closed_form(zeta), kRestitutionTolerance)
        << "zeta " << zeta;
}

TEST(PenaltyContact, RestitutionWithDampingBothWaysClampedAtZeroForce) {
  for (double zeta : {0.05, 0.1, 0.2, 0.5})
    EXPECT_NEAR(restitution(zeta, Damping::both_ways), both_ways_closed_form(zeta), kRestitutionTolerance)
        << "zeta " << zeta;
}

TEST(PenaltyContact, UndampedContactIsElastic) {
  // zeta = 0: both laws are a plain spring and e = 1 (same integration tolerance).
  EXPECT_NEAR(restitution(0.0, Damping::approach_only), 1.0, kRestitutionTolerance);
  EXPECT_NEAR(restitution(0.0, Damping::both_ways), 1.0, kRestitutionTolerance);
}

TEST(PenaltyContact, DampingCoefficientIsTheFractionOfCritical) {
  // Hand-worked: k = 100 N/m, m = 4 kg: critical c = 2 sqrt(400) = 40 N s/m.
  EXPECT_DOUBLE_EQ(damping_coefficient(1.0, 100.0, 4.0), 40.0);
  EXPECT_DOUBLE_EQ(damping_coefficient(0.25, 100.0, 4.0), 10.0);
}

TEST(PenaltyContact, NormalForceNeverPulls) {
  // Separating fast at small depth: k d = 1 N, c v = 5 N; both-ways damping would pull.
  EXPECT_EQ(normal_force(100.0, 0.01, 0.5, 10.0, Damping::both_ways).force_N, 0.0);
  // Approach-only damping leaves the spring alone while separating: 1 N.
  EXPECT_DOUBLE_EQ(normal_force(100.0, 0.01, 0.5, 10.0, Damping::approach_only).force_N, 1.0);
  // Approaching at 0.5 m/s: 1 N + 5 N for both.
  EXPECT_DOUBLE_EQ(normal_force(100.0, 0.01, -0.5, 10.0, Damping::approach_only).force_N, 6.0);
  EXPECT_DOUBLE_EQ(normal_force(100.0, 0.01, -0.5, 10.0, Damping::both_ways).force_N, 6.0);
}

TEST(PenaltyContact, ApproachDampingPowerIsTheDampersWork) {
  // Over one approach at zeta = 0.2 (damping on approach only), the damper's
  // work is what the particle loses on the way in: (1/2) m v0^2 minus the
  // spring energy at the deepest point, (1/2) m (e v0)^2 with e the closed form.
  const double k = 1.0e4, m = 0.01, v0 = 1.0, zeta = 0.2;
  const double omega = std::sqrt(k / m), dt = 1.0e-5 / omega;
  const double c = damping_coefficient(zeta, k, m);
  double z = 0.0, v = -v0, work = 0.0;
  while (v < 0.0) {
    const NormalForce n = normal_force(k, -z, v, c, Damping::approach_only);
    work += approach_damping_power(n, v) * dt;
    v += n.force_N / m * dt;
    z += v * dt;
  }
  const double e = approach_only_closed_form(zeta);
  // Relative tolerance: the same first-order integration error as the restitution (1e-4).
  EXPECT_NEAR(work, 0.5 * m * v0 * v0 * (1.0 - e * e), kRestitutionTolerance * 0.5 * m * v0 * v0);
}

TEST(PenaltyContact, CoulombConeKeepsStickAndScalesSlip) {
  // Hand-worked: a trial force of 5 N against a cone of 3 N slides at 3/5 of it.
  const CoulombCap slip = coulomb_cap(5.0, 3.0);
  EXPECT_TRUE(slip.sliding);
  EXPECT_DOUBLE_EQ(slip.scale, 0.6);
  const CoulombCap stick = coulomb_cap(2.0, 3.0);
  EXPECT_FALSE(stick.sliding);
  EXPECT_EQ(stick.scale, 1.0);
  // On the cone it still sticks (|f_t| <= mu f_n); with no friction the spring is released.
  EXPECT_FALSE(coulomb_cap(3.0, 3.0).sliding);
  EXPECT_EQ(coulomb_cap(2.0, 0.0).scale, 0.0);
}

TEST(PenaltyContact, SpringSliderDissipatesMuFnTimesTheSlip) {
  // A stick spring kt dragged a distance D in small steps under a constant cap
  // mu f_n (a Prandtl element): it sticks until kt u = cap, at u* = cap / kt,
  // then slides. Work done = stored energy cap^2 / (2 kt) + cap (D - u*).
  const double kt = 2.0e4, cap = 30.0, D = 0.01;
  const int steps = 1000;
  const double du = D / steps;
  double spring = 0.0, dissipated = 0.0, work = 0.0;
  for (int s = 0; s < steps; ++s) {
    const double before = spring;
    const double trial = spring + kt * du;
    const CoulombCap map = coulomb_cap(trial, cap);
    spring = trial;
    if (map.sliding) dissipated += slip_dissipation(trial, cap, kt), spring *= map.scale;
    work += 0.5 * (before + spring) * du;  // not exact in the step that starts sliding
  }
  const double u_star = cap / kt;
  // Tolerance 1e-12 relative: the sum is exact but for rounding over 1000 steps.
  EXPECT_NEAR(dissipated, cap * (D - u_star), 1e-12 * cap * D);
  EXPECT_DOUBLE_EQ(spring, cap);
  // Energy balance, to the trapezoidal work's error in the one step where the
  // spring reaches the cap (at most cap du / 2).
  EXPECT_NEAR(work, dissipated + cap * cap / (2.0 * kt), 0.5 * cap * du);
}

TEST(PenaltyContact, VelocityStopFrictionBrakesAtMuG) {
  // A block at 2 m/s sliding on a plane with mu = 0.5 under its weight stops
  // after v0^2 / (2 mu g) = 0.4077 m and then stays at rest.
  const double m = 3.0, g = 9.81, mu = 0.5, v0 = 2.0, dt = 1e-6;
  double v = v0, x = 0.0;
  for (int s = 0; s < 2000000; ++s) {
    const double ft = v > 0.0 ? velocity_stop_friction(mu * m * g, m, v, dt) : 0.0;
    v -= ft / m * dt;
    x += v * dt;
  }
  // At rest to rounding: the last step removes m v / dt, i.e. v, to an ulp of 2 m/s.
  EXPECT_NEAR(v, 0.0, 1e-15);
  // Tolerance: explicit Euler's stopping distance is off by about v0 dt per
  // unit of time braking (0.4 s), i.e. ~1e-6 m; 1e-5 m is ten times that.
  EXPECT_NEAR(x, v0 * v0 / (2.0 * mu * g), 1e-5);
}

}  // namespace
