// Force decomposition of thesis chapter 2 (coupler/forces.hpp) on analytic
// contact patches. Expected values are worked out by hand in each test from the
// definitions in docs/force_decomposition.md (thesis eqs. 2.1, 2.2, 5.1, Figs. 2.1, 2.2).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cosim/error.hpp"
#include "coupler/forces.hpp"

using coupler::FacetTag;

namespace {

constexpr double kTol = 1e-9;  // relative; sums of a few terms in double precision

struct V {
  double x = 0, y = 0, z = 0;
};

// Appends one contacted facet: pressure force P, friction force T, centroid c.
void add(coupler::FacetLoads& l, FacetTag tag, V p, V t, V c, double area) {
  l.tag.push_back(tag);
  l.pressure_x_N.push_back(p.x), l.pressure_y_N.push_back(p.y), l.pressure_z_N.push_back(p.z);
  l.friction_x_N.push_back(t.x), l.friction_y_N.push_back(t.y), l.friction_z_N.push_back(t.z);
  l.centroid_x_m.push_back(c.x), l.centroid_y_m.push_back(c.y), l.centroid_z_m.push_back(c.z);
  l.contact_area_m2.push_back(area);
}

// Pressure force of a facet with compressive normal force N and unit outward normal n: -N n.
V pressure(double n_force, V n) { return {-n_force * n.x, -n_force * n.y, -n_force * n.z}; }

coupler::WheelInput wheel(double rim_x, double r) {
  coupler::WheelInput w;
  w.rim_x_m = rim_x;
  w.rolling_radius_m = r;
  return w;
}

}  // namespace

TEST(CouplerForces, FlatPatchUniformPressureAndFrictionIsAllTraction) {
  // 4 x 3 facets of a x a at z = -0.05, centred under the rim at x = 1; p uniform, tau = 0.3 p forward.
  const double a = 0.02, p = 150e3, tau = 0.3 * p, rim_x = 1.0;
  coupler::FacetLoads l;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j)
      add(l, FacetTag::tread_top, {0, 0, p * a * a}, {tau * a * a, 0, 0}, {rim_x + (i - 1.5) * a, (j - 1.0) * a, -0.05},
          a * a);
  const auto d = coupler::decompose_forces(l, wheel(rim_x, 0.4));
  const double friction_total = 12 * tau * a * a;  // F3 = sum T_x (2.1.3)
  EXPECT_NEAR(d.traction_force_N, friction_total, kTol * friction_total);
  EXPECT_EQ(d.motion_resistance_N, 0.0);  // no longitudinal pressure component
  EXPECT_EQ(d.groove_force_N, 0.0);
  EXPECT_NEAR(d.vertical_pressure_force_N, 12 * p * a * a, kTol * p);
  EXPECT_NEAR(d.rolling_resistance_moment_Nm, 0.0, 1e-9);  // centre of pressure under the rim
  EXPECT_NEAR(d.drawbar_pull_N, friction_total, kTol * friction_total);
  EXPECT_NEAR(d.contact_area_m2, 12 * a * a, 1e-15);
  EXPECT_NEAR(d.sinkage_m, 0.05, 1e-15);  // terrain top at z = 0 (default)
}

TEST(CouplerForces, GrooveWallFacingForwardOrBackwardGivesSignedGrooveForce) {
  const double n_force = 200.0, c30 = std::cos(M_PI / 6), s30 = std::sin(M_PI / 6);
  struct Case {
    FacetTag tag;
    V normal;
    double expected_f2;  // F2 = P_x = -N n_x (2.1.2)
  };
  const Case cases[] = {{FacetTag::groove_wall, {1, 0, 0}, -n_force},   // faces forward: pushed back
                        {FacetTag::groove_wall, {-1, 0, 0}, n_force},   // faces backward: pushed forward
                        {FacetTag::groove_wall, {-c30, 0, -s30}, n_force * c30},
                        {FacetTag::sipe_wall, {-1, 0, 0}, n_force}};
  for (const Case& c : cases) {
    coupler::FacetLoads l;
    add(l, c.tag, pressure(n_force, c.normal), {}, {0.0, 0, -0.1}, 1e-4);
    const auto d = coupler::decompose_forces(l, wheel(0.0, 0.4));
    EXPECT_NEAR(d.groove_force_N, c.expected_f2, kTol * n_force);
    EXPECT_EQ(d.motion_resistance_N, 0.0);
    EXPECT_NEAR(d.net_longitudinal_pressure_force_N, c.expected_f2, kTol * n_force);  // eq. 2.2
    EXPECT_EQ(d.traction_force_N, 0.0);
  }
}

TEST(CouplerForces, LeadingEdgePressureIsMotionResistance) {
  // Tread top (and groove bottom) ahead of the rim, normal tilted forward by alpha:
  // P = -N (sin a, 0, -cos a), so F1 = -P_x = N sin a (2.1.1); a smooth cap has no F2 (5.3).
  const double n_force = 500.0, alpha = 0.3;
  for (FacetTag tag : {FacetTag::tread_top, FacetTag::groove_bottom, FacetTag::shoulder}) {
    coupler::FacetLoads l;
    add(l, tag, pressure(n_force, {std::sin(alpha), 0, -std::cos(alpha)}), {}, {0.1, 0, -0.09}, 2e-4);
    const auto d = coupler::decompose_forces(l, wheel(0.0, 0.4));
    EXPECT_NEAR(d.motion_resistance_N, n_force * std::sin(alpha), kTol * n_force);
    EXPECT_EQ(d.groove_force_N, 0.0);
    EXPECT_NEAR(d.net_longitudinal_pressure_force_N, -n_force * std::sin(alpha), kTol * n_force);
    EXPECT_NEAR(d.vertical_pressure_force_N, n_force * std::cos(alpha), kTol * n_force);
  }
}

TEST(CouplerForces, PressureCentreOffsetGivesRollingResistance) {
  // Rigid wheel, load W carried by two equal facets centred e ahead of the rim:
  // RRM = W e (Fig. 2.2, 2.1.4), F5 = W e / r.
  const double W = 4000.0, e = 0.011, r = 0.42, rim_x = 2.0;
  coupler::FacetLoads l;
  for (double dx : {-0.05, 0.05}) add(l, FacetTag::tread_top, {0, 0, W / 2}, {}, {rim_x + e + dx, 0, -0.4}, 1e-3);
  auto d = coupler::decompose_forces(l, wheel(rim_x, r));
  EXPECT_NEAR(d.rolling_resistance_moment_Nm, W * e, 1e-9 * W);
  EXPECT_NEAR(d.pressure_centre_offset_m, e, 1e-12);
  EXPECT_NEAR(d.rolling_resistance_force_N, W * e / r, 1e-9 * W);
  EXPECT_NEAR(d.drawbar_pull_N, -W * e / r, 1e-9 * W);  // towed, frictionless: DP = -F5
  EXPECT_NEAR(d.traction_minus_rrf_N, -W * e / r, 1e-9 * W);

  // Uneven loads 1000, 2000, 1000 N at -0.04, 0.01, 0.08 m: e = (-40 + 20 + 80) / 4000 = 0.015 m.
  coupler::FacetLoads u;
  const double f[] = {1000, 2000, 1000}, x[] = {-0.04, 0.01, 0.08};
  for (int i = 0; i < 3; ++i) add(u, FacetTag::tread_top, {0, 0, f[i]}, {}, {x[i], 0, -0.4}, 1e-3);
  d = coupler::decompose_forces(u, wheel(0.0, r));
  EXPECT_NEAR(d.pressure_centre_offset_m, 0.015, 1e-12);
  EXPECT_NEAR(d.rolling_resistance_force_N, 4000 * 0.015 / r, 1e-9 * W);
}

TEST(CouplerForces, MeasuredRm2GivesRollingResistanceForce) {
  // Thesis 5.2.3: towed smooth cap tyre in soft snow, RRM = RM2 = 45 N m, zero-slip radius 0.42 m.
  coupler::FacetLoads l;
  add(l, FacetTag::tread_top, {0, 0, 4000}, {}, {0, 0, -0.4}, 1e-3);  // centred: pressure RRM would be 0
  coupler::WheelInput w = wheel(0.0, 0.42);
  w.reaction_moment_y_Nm = 45.0;
  coupler::DecompositionOptions o;
  o.rrm_source = coupler::RrmSource::reaction_moment;
  const auto d = coupler::decompose_forces(l, w, o);
  EXPECT_NEAR(d.rolling_resistance_moment_Nm, 45.0, 1e-12);
  EXPECT_NEAR(d.rolling_resistance_force_N, 45.0 / 0.42, 1e-9);
  EXPECT_EQ(d.pressure_centre_offset_m, 0.0);
}

TEST(CouplerForces, DrawbarPullOnAMixedPatchWorkedByHand) {
  // Five facets; every expected value below is a number worked out by hand from
  // the definitions of docs/force_decomposition.md (thesis 2.1.1-2.1.4, eq. 2.1),
  // not an expression of the code's formulas.
  const double r = 0.4;
  coupler::FacetLoads l;
  add(l, FacetTag::tread_top, {0, 0, 1500}, {300, 10, 0}, {0.02, 0, -0.38}, 4e-3);  // friction 300 forward
  add(l, FacetTag::tread_top, {-80, 0, 600}, {50, 0, 5}, {0.12, 0, -0.36}, 2e-3);   // leading edge
  add(l, FacetTag::groove_wall, {120, 0, 0}, {0, 0, -4}, {-0.03, 0, -0.37}, 5e-4);  // faces back: +120
  add(l, FacetTag::groove_wall, {-30, 0, 0}, {0, 0, 2}, {0.05, 0, -0.37}, 5e-4);    // faces forward: -30
  add(l, FacetTag::sipe_wall, {15, 0, 0}, {0, 0, 0}, {0.0, 0, -0.37}, 1e-4);
  const auto d = coupler::decompose_forces(l, wheel(0.0, r));
  // By hand:
  //   F1  = -(P_x of the non-groove facets) = -(0 - 80)         =  80 N
  //   F2  =   P_x of the groove facets      = 120 - 30 + 15      = 105 N
  //   F3  =   sum T_x                       = 300 + 50           = 350 N
  //   RRM =   sum P_z (x - x_rim)           = 1500 (0.02) + 600 (0.12) = 30 + 72 = 102 N m
  //   F5  =   RRM / r                       = 102 / 0.4          = 255 N
  //   DP  =   F2 + F3 - F1 - F5             = 105 + 350 - 80 - 255 = 120 N   (eq. 2.1)
  //   -F1 + F2                              = 25 N                          (eq. 2.2)
  // Tolerance 1e-9 N: each value is a sum of at most five terms of order 1e3 N in
  // double precision (rounding ~1e-13 N); a wrong sign or a facet in the wrong
  // class changes a value by 10 N or more.
  EXPECT_NEAR(d.motion_resistance_N, 80.0, 1e-9);
  EXPECT_NEAR(d.groove_force_N, 105.0, 1e-9);
  EXPECT_NEAR(d.traction_force_N, 350.0, 1e-9);
  EXPECT_NEAR(d.rolling_resistance_moment_Nm, 102.0, 1e-9);
  EXPECT_NEAR(d.rolling_resistance_force_N, 255.0, 1e-9);
  EXPECT_NEAR(d.drawbar_pull_N, 120.0, 1e-9);
  EXPECT_NEAR(d.net_longitudinal_pressure_force_N, 25.0, 1e-9);
  EXPECT_NEAR(d.traction_minus_rrf_N, 350.0 - 255.0, 1e-9);
  // The inline eq. 2.1 on its own, with the hand values: 120 N. The four inputs are
  // distinct, so a swapped argument or a flipped sign gives another number
  // (e.g. +F1: 280, +F5: 630, F1 and F2 swapped: 70). The inputs and all partial
  // sums are integers, exact in double precision, hence the tolerance 0.
  EXPECT_EQ(coupler::drawbar_pull(80.0, 105.0, 350.0, 255.0), 120.0);
  EXPECT_EQ(coupler::net_longitudinal_pressure_force(80.0, 105.0), 25.0);
}

TEST(CouplerForces, DrawbarPullIsNetLongitudinalForceMinusMomentRrf) {
  // A physical identity the code does not use to compute DP: F1, F2 and F3 split the
  // whole longitudinal contact force on the tyre, so DP = sum_i (P_x,i + T_x,i) - F5,
  // here with F5 from the measured rim moment (towed tyre, thesis 5.2.3: RRM = RM2).
  // The net force is summed facet by facet below, without the tag split; the code sums
  // F1, F2, F3 separately by tag. Loads on a tread-patterned patch, three groove tags.
  const double r = 0.42, rm2 = 45.0;  // thesis 5.2.3: 45 N m, zero-slip radius 0.42 m
  coupler::FacetLoads l;
  add(l, FacetTag::tread_top, {-35, 3, 900}, {120, -6, 1}, {0.03, 0.01, -0.38}, 3e-3);
  add(l, FacetTag::groove_bottom, {-12, 0, 300}, {20, 0, 0}, {0.08, -0.02, -0.37}, 1e-3);
  add(l, FacetTag::groove_wall, {60, 0, 4}, {-5, 0, 0}, {-0.02, 0.03, -0.37}, 4e-4);
  add(l, FacetTag::groove_wall, {-18, 1, 2}, {3, 0, 0}, {0.06, 0.03, -0.37}, 4e-4);
  add(l, FacetTag::sipe_wall, {9, 0, 0}, {1, 0, 0}, {0.01, 0.0, -0.38}, 1e-4);
  add(l, FacetTag::shoulder, {-7, 2, 150}, {-4, 0, 0}, {0.1, 0.1, -0.33}, 5e-4);
  coupler::WheelInput w = wheel(0.0, r);
  w.reaction_moment_y_Nm = rm2;
  coupler::DecompositionOptions o;
  o.rrm_source = coupler::RrmSource::reaction_moment;
  const auto d = coupler::decompose_forces(l, w, o);
  // Net longitudinal contact force, by hand: pressure -35 - 12 + 60 - 18 + 9 - 7 = -3 N,
  // friction 120 + 20 - 5 + 3 + 1 - 4 = 135 N, total 132 N; F5 = 45 / 0.42 = 107.142857... N.
  const double net_x = 132.0, f5 = 45.0 / 0.42;
  // Tolerance: 1e-9 N against forces of order 1e2 N (double-precision rounding
  // ~1e-13 N); a facet dropped or counted twice changes DP by at least 1 N.
  EXPECT_NEAR(d.rolling_resistance_force_N, f5, 1e-9);
  EXPECT_NEAR(d.drawbar_pull_N, net_x - f5, 1e-9);
  EXPECT_NEAR(d.net_longitudinal_pressure_force_N, -3.0, 1e-9);  // eq. 2.2: the pressure part alone
}

TEST(CouplerForces, SinkageAndContactArea) {
  coupler::FacetLoads l;
  add(l, FacetTag::tread_top, {0, 0, 10}, {}, {0, 0, -0.03}, 1e-3);
  add(l, FacetTag::groove_bottom, {0, 0, 10}, {}, {0, 0, -0.05}, 2e-3);
  add(l, FacetTag::tread_top, {}, {}, {0, 0, -0.08}, 0.0);  // listed but not in contact
  coupler::DecompositionOptions o;
  o.terrain_surface_z_m = 0.01;
  auto d = coupler::decompose_forces(l, wheel(0.0, 0.4), o);
  EXPECT_NEAR(d.sinkage_m, 0.01 + 0.05, 1e-15);
  EXPECT_NEAR(d.contact_area_m2, 3e-3, 1e-15);
  coupler::WheelInput w = wheel(0.0, 0.4);
  w.rim_z_m = 0.352;
  o.sinkage = coupler::SinkageMeasure::rim_drop;
  o.reference_rim_z_m = 0.39;
  d = coupler::decompose_forces(l, w, o);
  EXPECT_NEAR(d.sinkage_m, 0.39 - 0.352, 1e-15);
  d = coupler::decompose_forces({}, wheel(0.0, 0.4));  // no contact at all
  EXPECT_EQ(d.sinkage_m, 0.0);
  EXPECT_EQ(d.contact_area_m2, 0.0);
  EXPECT_EQ(d.drawbar_pull_N, 0.0);
}

TEST(CouplerForces, RejectsInconsistentInput) {
  coupler::FacetLoads l;
  add(l, FacetTag::tread_top, {0, 0, 10}, {}, {0, 0, -0.03}, 1e-3);
  EXPECT_THROW(coupler::decompose_forces(l, wheel(0.0, 0.0)), cosim::Error);  // r must be > 0
  auto bad = l;
  bad.friction_x_N.push_back(1.0);
  EXPECT_THROW(coupler::decompose_forces(bad, wheel(0.0, 0.4)), cosim::Error);
  bad = l;
  bad.contact_area_m2[0] = -1e-3;
  EXPECT_THROW(coupler::decompose_forces(bad, wheel(0.0, 0.4)), cosim::Error);
  bad = l;
  bad.pressure_z_N[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(coupler::decompose_forces(bad, wheel(0.0, 0.4)), cosim::Error);
}

TEST(CouplerForces, LiftSplitsIntoTreadTopsAndPatternRecesses) {
  // Water under a grooved tread: where does it lift the tyre? Six facets, one of
  // each tag that can touch the terrain, each with a distinct power-of-two lift so
  // that a tag counted in the wrong part, twice or not at all gives another sum:
  //   tread tops     : 1 + 2           = 3 N
  //   recesses       : groove wall 4 + groove floor 8 + sipe wall 16 = 28 N
  //   neither (rest) : shoulder 32     (and a sidewall pushed down, -64)
  //   F4 = 3 + 28 + 32 - 64 = -1 N.
  // Sums of integers are exact in double precision, hence the tolerance 0.
  coupler::FacetLoads l;
  add(l, FacetTag::tread_top, {0, 0, 1}, {}, {0, 0, -0.38}, 1e-3);
  add(l, FacetTag::tread_top, {0, 0, 2}, {}, {0.01, 0, -0.38}, 1e-3);
  add(l, FacetTag::groove_wall, {-3, 0, 4}, {}, {0.02, 0, -0.37}, 1e-4);
  add(l, FacetTag::groove_bottom, {0, 0, 8}, {}, {0.03, 0, -0.37}, 1e-4);
  add(l, FacetTag::sipe_wall, {1, 0, 16}, {}, {0.04, 0, -0.37}, 1e-4);
  add(l, FacetTag::shoulder, {0, 5, 32}, {}, {0.0, 0.1, -0.36}, 1e-4);
  add(l, FacetTag::sidewall, {0, 5, -64}, {}, {0.0, 0.12, -0.30}, 1e-4);
  const auto d = coupler::decompose_forces(l, wheel(0.0, 0.4));
  EXPECT_EQ(d.vertical_pressure_force_N, -1.0);
  EXPECT_EQ(d.vertical_pressure_force_tread_top_N, 3.0);
  EXPECT_EQ(d.vertical_pressure_force_groove_N, 28.0);
}
