// The axisymmetric dynamic-relaxation solver (tyre_fe/axisym.hpp) on Lame's
// pressurised thick cylinder in plane strain (Timoshenko & Goodier, Theory of
// Elasticity, 3rd ed., 1970, section 28): inner radius a, outer b, internal pressure p,
//   u(r)       = (1 + nu) a^2 p / (E (b^2 - a^2)) ((1 - 2 nu) r + b^2 / r),
//   sigma_r    = p a^2 / (b^2 - a^2) (1 - b^2 / r^2),
//   sigma_th   = p a^2 / (b^2 - a^2) (1 + b^2 / r^2),
//   sigma_y    = nu (sigma_r + sigma_th)          (plane strain: every node's y held).
// Two materials: the tread rubber of thesis Table 5.4 ($COSIM_TEST_DATA/rubber_yeoh.csv)
// with K0 / mu0 = 1000 (nu = 0.4995), and St. Venant-Kirchhoff with nu = 0.3. The
// pressure keeps strains below 5e-4 so that the finite-strain response is linear to
// well below the tolerances.
//
// Twist (TyreTwist tests): the same cylinder with a band of smeared rebar running
// spirally in the r-theta plane (layer tangent e_r, bars at angle alpha towards
// theta, like the ply of a sidewall). Under internal pressure the bars' tension has an
// r-theta shear component; with the twist dof the band shears until the total shear
// stress vanishes. Moment equilibrium of a ring between r and r + dr,
// d(r^2 tau_r-theta)/dr = 0, with a traction-free outer surface gives
// tau_r-theta = 0 at every radius, so the rubber outside the band is not sheared and
// in the band (small strain, fibre modulus E_l = phi E, shear modulus G)
//   G gamma + E_l s c (c^2 eps_r + s^2 eps_theta + s c gamma) = 0,  s, c = sin, cos alpha,
//   gamma = r dphi/dr = -E_l s c (c^2 eps_r + s^2 eps_theta) / (G + E_l s^2 c^2),
// so the outer surface turns by gamma t / r_band relative to the inner one (t the band
// thickness). Bars in tension (eps_fibre > 0) at +alpha turn it backwards (phi < 0).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tyre_fe/axisym.hpp"
#include "tyre_material_data.hpp"

namespace {

using namespace tyre_fe;

// Discretisation error of 16 one-point quads through the wall: O((h / a)^2) = 0.4 % with
// h / a = 0.0625 (observed 0.02-0.08 % on the displacements). The centroid stresses are
// element means of a field varying as 1/r^2 compared at the centroid radius, which
// adds O((h / r)^2) again (observed <= 0.17 %). Residual tolerance 1e-6.
constexpr double kDisplacementRelTol = 0.005;
constexpr double kHoopStressRelTol = 0.01;
constexpr double kOtherStressTol = 0.01;  // times p (sigma_r and sigma_y are O(p))

constexpr double kA = 0.1, kB = 0.2, kHeight = 0.01;
constexpr int kRadial = 16;

// n_radial x 1 quads on a <= r <= b, 0 <= y <= height; pressure on the r = a edges.
CrossSection thick_cylinder() {
  CrossSection s;
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= kRadial; ++i)
      s.nodes.emplace_back(kA + (kB - kA) * i / kRadial, kHeight * j);
  for (int i = 0; i < kRadial; ++i) {
    s.quads.push_back({i, i + 1, kRadial + 2 + i, kRadial + 1 + i});
    s.quad_region.push_back(Region::tread);
  }
  s.inner_liner_edges.push_back({0, 3});  // nodes 3 -> 0 of quad 0: the r = a edge
  return s;
}

struct Lame {
  double p, E, nu;
  double c() const { return p * kA * kA / (kB * kB - kA * kA); }
  double u(double r) const { return (1 + nu) * c() / E * ((1 - 2 * nu) * r + kB * kB / r); }
  double sigma_r(double r) const { return c() * (1 - kB * kB / (r * r)); }
  double sigma_theta(double r) const { return c() * (1 + kB * kB / (r * r)); }
};

void check_against_lame(const SolidMaterial& material, const Lame& lame) {
  const CrossSection section = thick_cylinder();
  TyreMaterials materials;
  materials.solid[static_cast<int>(Region::tread)] = material;
  AxisymLoadCase load;
  load.pressure_Pa = lame.p;
  load.fixed_nodes = std::vector<int>{};
  for (int n = 0; n < static_cast<int>(section.nodes.size()); ++n) load.fixed_y_nodes.push_back(n);

  const AxisymResult result = solve_axisym(section, materials, load);
  ASSERT_TRUE(result.converged) << "residual " << result.residual_ratio << " after " << result.steps;
  // Isotropic material: nothing drives the twist (tau_r-theta = tau_y-theta = 0 exactly).
  ASSERT_EQ(result.twist_rad.size(), section.nodes.size());
  for (double phi : result.twist_rad) EXPECT_EQ(phi, 0.0);
  std::printf("  %ld steps of %.3g s, residual ratio %.2e, hourglass/strain energy %.1e\n",
              result.steps, result.time_step_s, result.residual_ratio,
              result.hourglass_energy_J_per_rad / result.strain_energy_J_per_rad);

  for (int i : {0, kRadial}) {
    const double r = section.nodes[i][0];
    const double expected = lame.u(r);
    for (int node : {i, i + kRadial + 1}) {  // y = 0 and y = height
      const double u = result.nodes[node][0] - r;
      if (node == i)
        std::printf("  u(%.2f) = %.6e m, Lame %.6e, error %+.3f %%\n", r, u, expected, 100 * (u / expected - 1));
      EXPECT_NEAR(u, expected, kDisplacementRelTol * expected);
    }
  }
  for (int q : {0, kRadial / 2, kRadial - 1}) {
    double R = 0.0;
    for (int n : section.quads[q]) R += 0.25 * section.nodes[n][0];
    const Eigen::Matrix3d& sigma = result.quad_stress_Pa[q];
    const double hoop = lame.sigma_theta(R), radial = lame.sigma_r(R);
    std::printf("  r = %.4f: sigma_th %.5e (Lame %.5e, %+.3f %%), sigma_r %.4e (%.4e), sigma_y %.4e (%.4e)\n",
                R, sigma(2, 2), hoop, 100 * (sigma(2, 2) / hoop - 1), sigma(0, 0), radial,
                sigma(1, 1), lame.nu * (radial + hoop));
    EXPECT_NEAR(sigma(2, 2), hoop, kHoopStressRelTol * hoop);
    EXPECT_NEAR(sigma(0, 0), radial, kOtherStressTol * lame.p);
    EXPECT_NEAR(sigma(1, 1), lame.nu * (radial + hoop), kOtherStressTol * lame.p);
    EXPECT_NEAR(sigma(0, 1), 0.0, kOtherStressTol * lame.p);
  }
}

TEST(TyreLame, NearlyIncompressibleYeohRubber) {
  // density, C10, C20, C30 of the tread (thesis Table 5.4).
  SolidMaterial rubber = tyre_material_data::yeoh_rubber(tyre_material_data::csv_row("rubber_yeoh.csv", "tread"));
  const double mu = rubber.yeoh.initial_shear_modulus_Pa(), K = 1000 * mu;
  rubber.yeoh.bulk_modulus_Pa = K;
  // Small-strain constants of the Yeoh solid: mu0 = 2 C10, K0.
  const double E = 9 * K * mu / (3 * K + mu), nu = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  check_against_lame(rubber, Lame{1.0e3, E, nu});
}

TEST(TyreLame, CompressibleStVenantKirchhoff) {
  SolidMaterial solid;
  solid.kind = SolidMaterial::Kind::elastic;
  solid.elastic = ElasticSolid{5.0e6, 0.3, 1000.0};
  check_against_lame(solid, Lame{1.0e3, 5.0e6, 0.3});
}

// ---- twist: spiral rebar band in the r-theta plane --------------------------------

constexpr double kTwistPressure = 1.0e3;
constexpr double kSpiralAngle = 0.25 * 3.14159265358979323846;  // 45 deg
// Rebar of one band: phi E = 10 E of the host.
constexpr double kBarArea = 1.0e-6, kBarSpacing = 1.0e-3, kBarModulus = 3.125e8;
constexpr double kBand = (kB - kA) / kRadial;  // band (= quad) thickness

// Host: the compressible St. Venant-Kirchhoff solid (nu = 0.3). In nearly
// incompressible plane strain eps_r = -eps_theta, and bars at 45 deg would not stretch.
SolidMaterial twist_host() {
  SolidMaterial solid;
  solid.kind = SolidMaterial::Kind::elastic;
  solid.elastic = ElasticSolid{5.0e6, 0.3, 1000.0};
  return solid;
}

struct SpiralCase {
  std::vector<std::pair<int, double>> bands;  // (radial quad index, bar angle [rad])
  bool hold_inner_twist = true;   // else every twist is free (rigid rotation left to inertia)
  bool hold_all_twist = false;    // CAX4-like: no twist anywhere
  bool clamp_outer = false;       // outer surface in fixed_nodes (r, y and twist held, like a rim)
};

struct SpiralResult {
  CrossSection section;
  AxisymResult result;
};

SpiralResult solve_spiral(const SpiralCase& c) {
  SpiralResult out;
  CrossSection& s = out.section;
  s = thick_cylinder();
  s.quad_layer_tangent.assign(s.quads.size(), Eigen::Vector2d(1.0, 0.0));
  s.quad_layer_thickness_m.assign(s.quads.size(), kBand);
  TyreMaterials materials;
  for (auto& m : materials.solid) m = twist_host();
  const Region regions[2] = {Region::belt_1, Region::belt_2};
  for (std::size_t b = 0; b < c.bands.size(); ++b) {
    s.quad_region[c.bands[b].first] = regions[b];
    materials.rebar[static_cast<int>(regions[b])] =
        RebarLayer{kBarArea, kBarSpacing, c.bands[b].second, kBarModulus, 0.0};
  }
  AxisymLoadCase load;
  load.pressure_Pa = kTwistPressure;
  load.fixed_nodes = std::vector<int>{};
  const int n = static_cast<int>(s.nodes.size());
  for (int node = 0; node < n; ++node) {
    load.fixed_y_nodes.push_back(node);  // plane strain
    const bool inner = s.nodes[node][0] == kA, outer = s.nodes[node][0] == kB;
    if (c.clamp_outer && outer) load.fixed_nodes->push_back(node);
    else if (c.hold_all_twist || (c.hold_inner_twist && inner)) load.fixed_twist_nodes.push_back(node);
  }
  out.result = solve_axisym(s, materials, load);
  return out;
}

// Twist of the outer surface relative to the inner one (y = 0 nodes; y = height equal).
double outer_twist(const SpiralResult& r) {
  return r.result.twist_rad[kRadial] - r.result.twist_rad[0];
}

// gamma of a band quad from its one-point strains, by the closed form above.
double expected_band_twist(const SpiralResult& r, int quad, double angle) {
  const auto& q = r.section.quads[quad];
  double R = 0.0, rr = 0.0;
  for (int n : q) R += 0.25 * r.section.nodes[n][0], rr += 0.25 * r.result.nodes[n][0];
  // Rectangle: dr/dR from the two radial edges, eps_theta = r_c / R_c - 1.
  const double eps_r = 0.5 * ((r.result.nodes[q[1]][0] - r.result.nodes[q[0]][0]) +
                              (r.result.nodes[q[2]][0] - r.result.nodes[q[3]][0])) / kBand - 1.0;
  const double eps_theta = rr / R - 1.0;
  const double G = twist_host().shear_modulus_Pa();
  const double E_l = kBarArea / (kBarSpacing * kBand) * kBarModulus;
  const double s = std::sin(angle), c = std::cos(angle);
  const double gamma = -E_l * s * c * (c * c * eps_r + s * s * eps_theta) / (G + E_l * s * s * c * c);
  return gamma * kBand / rr;
}

TEST(TyreTwist, SpiralBandTwistsTheCylinderAndIsInEquilibrium) {
  const int band = kRadial / 2;
  const SpiralResult with_twist = solve_spiral({{{band, kSpiralAngle}}});
  const AxisymResult& r = with_twist.result;
  ASSERT_TRUE(r.converged) << "residual " << r.residual_ratio << " after " << r.steps;
  const double twist = outer_twist(with_twist), expected = expected_band_twist(with_twist, band, kSpiralAngle);
  std::printf("  %ld steps, residual ratio %.2e; outer surface twist %.6e rad, closed form %.6e (%+.3f %%)\n",
              r.steps, r.residual_ratio, twist, expected, 100 * (twist / expected - 1));
  EXPECT_LT(twist, 0.0);  // bars in tension at +alpha turn the outside backwards
  EXPECT_NEAR(twist, expected, 0.01 * std::abs(expected));
  // The twist is a rigid rotation outside the band (no r-theta shear in the rubber),
  // and the same at both ends (y = 0 and y = height).
  for (int i = 0; i <= kRadial; ++i) {
    const double phi = r.twist_rad[i];
    EXPECT_NEAR(r.twist_rad[i + kRadial + 1], phi, 1e-4 * std::abs(twist));
    if (i <= band) EXPECT_NEAR(phi, 0.0, 1e-4 * std::abs(twist));
    else EXPECT_NEAR(phi, twist, 1e-4 * std::abs(twist));
  }
  // Torque balance: the bars' r-theta shear (sigma_f s c) is carried back by the
  // rubber's in the band, so the total vanishes everywhere and the held inner surface
  // takes no moment.
  const double E_l = kBarArea / (kBarSpacing * kBand) * kBarModulus;
  const double bar_shear = E_l * r.quad_rebar_log_strain[band] * std::sin(kSpiralAngle) * std::cos(kSpiralAngle);
  std::printf("  band: bar shear stress %.4e Pa, total sigma_r-theta %.2e Pa\n", bar_shear,
              r.quad_stress_Pa[band](0, 2));
  EXPECT_GT(bar_shear, 1e-3 * kTwistPressure);
  for (std::size_t q = 0; q < r.quad_stress_Pa.size(); ++q) {
    EXPECT_NEAR(r.quad_stress_Pa[q](0, 2), 0.0, 1e-3 * bar_shear) << "quad " << q;
    EXPECT_NEAR(r.quad_stress_Pa[q](1, 2), 0.0, 1e-3 * bar_shear) << "quad " << q;
  }

  // Without any twist (CAX4) the band keeps the bars' shear, which the revolved 3D
  // model cannot hold, and is stiffer in the hoop direction.
  SpiralCase held{{{band, kSpiralAngle}}};
  held.hold_all_twist = true;
  const SpiralResult without = solve_spiral(held);
  ASSERT_TRUE(without.result.converged);
  const double u_twist = r.nodes[kRadial][0] - kB, u_held = without.result.nodes[kRadial][0] - kB;
  std::printf("  outer u with twist %.6e m, twist held %.6e m; band sigma_r-theta held %.4e Pa\n", u_twist,
              u_held, without.result.quad_stress_Pa[band](0, 2));
  EXPECT_GT(u_twist, u_held);
  EXPECT_GT(std::abs(without.result.quad_stress_Pa[band](0, 2)), 0.5 * bar_shear);

  // Every twist free: the rigid rotation is a zero-energy mode; the internal moments sum
  // to zero, so from rest the inertia-weighted mean twist stays 0 and the relative
  // twist is the same.
  SpiralCase free_case{{{band, kSpiralAngle}}};
  free_case.hold_inner_twist = false;
  const SpiralResult free_result = solve_spiral(free_case);
  ASSERT_TRUE(free_result.result.converged);
  std::printf("  every twist free: relative outer twist %.6e rad, inner %.3e rad\n", outer_twist(free_result),
              free_result.result.twist_rad[0]);
  EXPECT_NEAR(outer_twist(free_result), twist, 1e-3 * std::abs(twist));

  // fixed_nodes hold the twist too (the rim holds the bead against turning): with the
  // outer surface clamped the inner one turns the other way.
  SpiralCase clamped{{{band, kSpiralAngle}}};
  clamped.hold_inner_twist = false;
  clamped.clamp_outer = true;
  const SpiralResult clamped_result = solve_spiral(clamped);
  ASSERT_TRUE(clamped_result.result.converged);
  EXPECT_EQ(clamped_result.result.twist_rad[kRadial], 0.0);
  EXPECT_EQ(clamped_result.result.nodes[kRadial][0], kB);
  const double clamped_expected = expected_band_twist(clamped_result, band, kSpiralAngle);
  std::printf("  outer surface clamped: inner twist %.6e rad, closed form %.6e\n",
              clamped_result.result.twist_rad[0], -clamped_expected);
  EXPECT_NEAR(clamped_result.result.twist_rad[0], -clamped_expected, 0.01 * std::abs(clamped_expected));
}

TEST(TyreTwist, OpposedBandsCancelTheTwist) {
  // Bands at +alpha and -alpha next to each other (like the two belts): each turns
  // the material outside it by the closed-form amount with opposite signs; the net
  // twist of the outer surface is what remains of the small difference of the strains
  // at the two radii.
  const int band = kRadial / 2;
  const SpiralResult single = solve_spiral({{{band, kSpiralAngle}}});
  const SpiralResult both = solve_spiral({{{band, kSpiralAngle}, {band + 1, -kSpiralAngle}}});
  ASSERT_TRUE(single.result.converged && both.result.converged);
  const double net = outer_twist(both), one = outer_twist(single);
  const double expected = expected_band_twist(both, band, kSpiralAngle) +
                          expected_band_twist(both, band + 1, -kSpiralAngle);
  const double between = both.result.twist_rad[band + 1] - both.result.twist_rad[0];
  std::printf("  single band %.6e rad; +-alpha: between the bands %.6e, outer %.6e rad (closed form %.6e)\n",
              one, between, net, expected);
  EXPECT_LT(std::abs(net), 0.1 * std::abs(one));
  EXPECT_NEAR(between, expected_band_twist(both, band, kSpiralAngle), 0.01 * std::abs(one));
  EXPECT_NEAR(net, expected, 0.01 * std::abs(one));
}

}  // namespace
