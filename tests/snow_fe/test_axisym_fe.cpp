// Tests of the Lagrangian axisymmetric snow mesh (snow_fe/axisym_fe.hpp) against
// closed forms of linear elasticity, and of the finite-element plate test
// (snow_fe/plate_fe.hpp) against its own conservation laws.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "snow_fe/axisym_fe.hpp"
#include "snow_fe/plate_fe.hpp"
#include "snow_sph/scene.hpp"
#include "test_support.hpp"

namespace {

namespace fe = snow_fe::axisym;

// A snow that stays elastic: the cone's cohesion and the cap's pressures are far
// beyond any stress of these tests (Table 3.1's E and nu).
snow_sph::MdpcParameters elastic_snow() {
  snow_sph::MdpcParameters p;
  p.youngs_modulus_Pa = 13.79e6;
  p.poisson_ratio = 0.3;
  p.cohesion_Pa = 1e12;
  p.friction_angle_rad = 0.4;
  p.cap_eccentricity = 0.02;
  p.hardening_pressure_Pa = {1e12, 2e12};
  p.hardening_volumetric_plastic_strain = {0.0, 1.0};
  return p;
}

std::vector<double> lines(double a, double b, int n) {
  std::vector<double> v;
  for (int k = 0; k <= n; ++k) v.push_back(a + (b - a) * k / n);
  return v;
}

// Dynamic relaxation to the static state: steps until the largest node speed
// has fallen below `speed_tol` after the ramp. prescribe(t) sets held velocities.
template <class Prescribe, class Load>
void relax(fe::Mesh& m, const snow_sph::MdpcParameters& p, double g, double ramp_s, double damping,
           double speed_tol, Prescribe prescribe, Load load) {
  const double c = std::sqrt((p.bulk_modulus_Pa() + 4.0 * p.shear_modulus_Pa() / 3.0) / m.density_kg_per_m3);
  std::vector<double> f_r, f_z, a_r, a_z;
  fe::element_pass(m, p, 0.0, f_r, f_z);
  load(0.0, f_r, f_z);
  fe::nodal_accelerations(m, f_r, f_z, g, a_r, a_z);
  double t = 0.0, dt_prev = 0.0;
  for (long step = 0; step < 2000000; ++step) {
    const double dt = fe::stable_time_step(m, c, 0.4);
    prescribe(t + 0.5 * dt);
    fe::advance_nodes(m, a_r, a_z, step == 0 ? 0.5 * dt : 0.5 * (dt + dt_prev), dt, damping);
    fe::element_pass(m, p, dt, f_r, f_z);
    t += dt, dt_prev = dt;
    load(t, f_r, f_z);
    fe::nodal_accelerations(m, f_r, f_z, g, a_r, a_z);
    if (t > ramp_s) {
      double vmax = 0.0;
      for (int k = 0; k < m.nodes(); ++k) vmax = std::max(vmax, std::hypot(m.v_r[k], m.v_z[k]));
      if (vmax < speed_tol) return;
    }
  }
  FAIL() << "dynamic relaxation did not converge";
}

// Plane-strain thick cylinder (Lame): inner radius a pushed out by u0, outer
// radius b free, z held. u(r) = A r + B / r with sigma_rr(b) = 0:
// B = (lambda + mu) A b^2 / mu, A = u0 / (a + (lambda + mu) b^2 / (mu a)).
double lame_outer_error(int elements) {
  const auto p = elastic_snow();
  const double a = 0.1, b = 0.3, u0 = 1e-5, ramp = 0.02;
  fe::Mesh m = fe::make_mesh(lines(a, b, elements), lines(0.0, 0.02, 1), 180.0, p);
  for (int k = 0; k < m.nodes(); ++k) m.hold_z[k] = 1;
  for (int j = 0; j < m.nodes_z; ++j) m.hold_r[m.node(0, j)] = 1;
  auto prescribe = [&](double t) {  // a smooth ramp of the inner face's displacement
    const double u = t >= ramp ? 0.0 : u0 * 6.0 * t * (ramp - t) / (ramp * ramp * ramp);
    for (int j = 0; j < m.nodes_z; ++j) m.v_r[m.node(0, j)] = u;
  };
  relax(m, p, 0.0, ramp, 2000.0, 1e-9, prescribe, [](double, auto&, auto&) {});
  const double E = p.youngs_modulus_Pa, nu = p.poisson_ratio;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const double A = u0 / (a + (lambda + mu) * b * b / (mu * a)), B = (lambda + mu) * A * b * b / mu;
  const double exact = A * b + B / b, inner = m.r_m[m.node(0, 0)] - a;
  const double fe_outer = m.r_m[m.node(m.nodes_r - 1, 0)] - b;
  std::printf("Lame, %d elements: inner %.4e m (set %.1e), outer %.6e m, exact %.6e m\n", elements, inner, u0,
              fe_outer, exact);
  return std::abs(fe_outer / exact - 1.0);
}

TEST(AxisymFe, ThickCylinderConvergesToLameAtSecondOrder) {
  // The hoop terms (N_a / r) and the B-bar volumetric operator are what this
  // exercises. Bilinear elements converge at second order in h: halving h must
  // cut the error about four times (3 allows for the relaxation's residual), and
  // with 8 elements across the wall the error is already below 1 %.
  const double coarse = lame_outer_error(8), fine = lame_outer_error(16);
  EXPECT_LT(coarse, 0.01);
  EXPECT_GT(coarse / fine, 3.0) << "coarse " << coarse << ", fine " << fine;
}

TEST(AxisymFe, ColumnUnderGravitySettlesAsTheClosedForm) {
  // An elastic column in uniaxial strain under its own weight: the top settles
  // rho g H^2 / (2 M), M = K + 4G/3. Lumped row-sum masses give the consistent
  // nodal loads of a uniform body force, so linear elements are nodally exact in
  // 1D; what is left is the relaxation's residual (speed < 1e-8 m/s) and the
  // geometric update (strains ~5e-5): 1e-3 relative.
  const auto p = elastic_snow();
  const double H = 0.5, g = 9.81, rho = 180.0;
  fe::Mesh m = fe::make_mesh(lines(0.0, 0.05, 2), lines(0.0, H, 25), rho, p);
  for (int j = 0; j < m.nodes_z; ++j) m.hold_r[m.node(0, j)] = m.hold_r[m.node(m.nodes_r - 1, j)] = 1;
  for (int i = 0; i < m.nodes_r; ++i) m.hold_z[m.node(i, 0)] = 1;
  relax(m, p, g, 0.0, 200.0, 1e-8, [](double) {}, [](double, auto&, auto&) {});
  const double M = p.bulk_modulus_Pa() + 4.0 * p.shear_modulus_Pa() / 3.0;
  const double exact = rho * g * H * H / (2.0 * M);
  for (int i = 0; i < m.nodes_r; ++i)
    EXPECT_NEAR(H - m.z_m[m.node(i, m.nodes_z - 1)], exact, 1e-3 * exact) << "top node " << i;
}

TEST(PlateFe, EnergyAndMomentumBalance) {
  // The plate scene's snow on a 30 mm mesh for 0.1 s (the load ramping up, the
  // snow yielding under it). Energy: the applied load's and gravity's work equals
  // kinetic + elastic energy + plastic work; the kinematic contact removes the
  // relative normal velocity of each contacting node (an inelastic impact per
  // step, O(dt) of the work) and central differences add O(dt^2): measured
  // 0.03 % here; 1 % would flag a missing force term (a wrong hoop force or
  // friction impulse is tens of percents). Momentum of the plate: the impulse the
  // snow gave it equals the load's impulse plus its weight's less its momentum,
  // integral F_snow = integral F_load + M g t + M v(t), up to the trapezoidal
  // integration of the smooth load over 0.5 ms rows (1e-4 of it; measured 0.04 %
  // in all): 0.5 %.
  const auto scene = cosim::load_scene(test_support::source_dir() + "/configs/scenes/plate_sinkage.textproto",
                                       {"time.end_time_s=0.1"});
  const auto setup = snow_fe::plate_fe_setup_from_scene(*scene, 0.03);
  const std::string out = testing::TempDir() + "plate_fe";
  const auto summary = snow_fe::run_plate_fe(setup, out, true);
  ASSERT_EQ(summary["status"], "completed");
  std::ifstream csv(out + "/plate.csv");
  std::string line;
  std::getline(csv, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
    rows.push_back(v);
  }
  ASSERT_GT(rows.size(), 100u);
  double snow_impulse = 0.0, load_impulse = 0.0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double span = rows[k][0] - rows[k - 1][0];
    snow_impulse += rows[k][3] * span;  // each row's force is the mean over its span
    load_impulse += 0.5 * (rows[k][4] + rows[k - 1][4]) * span;
  }
  const auto& end = rows.back();
  const double t = end[0], v = end[2], M = setup.plate_mass_kg, g = setup.gravity_m_per_s2;
  const double expected = load_impulse + M * g * t + M * v;
  const double external = end[8], balance = end[9];
  std::printf("plate FE: external work %.3f J, balance %.2e J; snow impulse %.3f N s, load + weight - momentum %.3f N s\n",
              external, balance, snow_impulse, expected);
  EXPECT_GT(external, 1.0);
  EXPECT_LT(std::abs(balance), 0.01 * external);
  EXPECT_NEAR(snow_impulse, expected, 0.005 * load_impulse);
}

}  // namespace
