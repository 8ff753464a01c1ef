// Axisymmetric dynamic relaxation (see axisym.hpp).
//
// Damping: kinetic damping (Cundall 1976; Barnes 1999, Int. J. Space Structures
// 14:89-104). The motion is undamped, and whenever the total kinetic energy (twist
// included) falls (a peak has just been passed, the structure is near a minimum of
// the potential energy along its path) every
// velocity is set to zero and the motion restarts from rest. It needs no estimate of
// the lowest frequency. Measured against mass-proportional damping set each step to
// critical damping of the lowest mode from the secant Rayleigh quotient
// u.f_int / u.M u (Underwood 1983; Papadrakakis 1981), to a residual ratio of 1e-6:
//   Lame cylinder (test_tyre_lame), Yeoh K0/mu0 = 1000:      4 634 vs 12 965 steps
//   generated 235/75R15 section, 532 quads, 200 kPa:       118 498 vs 155 921 steps
//   same with mass_scaling_time_step_s = 1e-6:               78 213 vs  90 512 steps
//   rubber-only torus, 120 quads, 5 kPa (soft, large u):     29 474 vs 135 863 steps
// The Rayleigh quotient of the current displacement overestimates omega_1 (the static
// shape is not a pure mode), which over-damps the slowest mode. (These counts predate
// the twist dof; with it the 235/75R15 section takes 127 461 steps, the same step.)
#include "tyre_fe/axisym.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/LU>  // determinant

#include "cosim/error.hpp"
#include "tyre_fe/elements.hpp"

namespace tyre_fe {
namespace {

constexpr double kSafetyFactor = 0.8;  // on the rigorous element bound of the critical step
constexpr long kProgressInterval = 1000;
constexpr double kPi = 3.14159265358979323846;

struct QuadData {
  Quad4AxiReference ref;
  std::array<int, 4> nodes;
  const SolidMaterial* solid;
  double shear_modulus_Pa;
  Eigen::Vector3d a0;      // reference bar direction (r, y, theta)
  double volume_fraction;  // 0: no rebar
  double fibre_modulus_Pa;
};

struct QuadState {
  double f[4][2];
  double moment[4];  // conjugate to the twist angles
  double strain_energy;
  double hourglass_energy;
};

// Dofs of node n: 3 n (r), 3 n + 1 (y), 3 n + 2 (phi). The state is the flat array
// of current values (r, y, phi) per node.
constexpr int kDofsPerNode = 3;

struct Model {
  std::vector<QuadData> quads;
  // Per dof, so that the step loops need no branches: the mass (m, m, m R^2 for the
  // twist), its inverse (0 on held dofs, which therefore never move) and the weight
  // of the squared residual (1, 1, 1 / R^2: the moment as a hoop force; 0 if held).
  std::vector<double> mass;
  std::vector<double> inverse_mass;
  std::vector<double> residual_weight;
  double time_step_s = 0.0;
  double ramp_time_s = 0.0;
};

[[noreturn]] void fail(const std::string& what) { throw cosim::Error("solve_axisym: " + what); }

void check_node(int node, std::size_t count, const char* list) {
  if (node < 0 || static_cast<std::size_t>(node) >= count)
    fail(std::string(list) + " has node " + std::to_string(node) + " out of range");
}

// The dofs held from the start: every dof of the fixed nodes (the rim's by default).
std::vector<char> held_dofs(const CrossSection& s, const AxisymLoadCase& load) {
  const std::size_t n_nodes = s.nodes.size();
  std::vector<char> fixed(kDofsPerNode * n_nodes, 0);
  const std::vector<int>& fixed_nodes = load.fixed_nodes ? *load.fixed_nodes : s.rim_nodes;
  for (int node : fixed_nodes) {
    check_node(node, n_nodes, "fixed_nodes");
    for (int c = 0; c < kDofsPerNode; ++c) fixed[kDofsPerNode * node + c] = 1;
  }
  return fixed;
}

// The quad's bars, smeared into it as a volume fraction along a0 (r, y, theta);
// adds their density to the quad's, `density`.
void set_quad_rebar(const CrossSection& s, const RebarLayer& bar, std::size_t q, const std::string& name,
                    QuadData& d, double& density) {
  if (s.quad_layer_tangent.size() != s.quads.size() ||
      s.quad_layer_thickness_m.size() != s.quads.size())
    fail("rebar needs quad_layer_tangent and quad_layer_thickness_m for every quad");
  const Eigen::Vector2d t = s.quad_layer_tangent[q];
  const double thickness = s.quad_layer_thickness_m[q];
  if (!(t.norm() > 0.5) || !(thickness > 0.0) || !(bar.spacing_m > 0.0) ||
      !(bar.youngs_modulus_Pa > 0.0) || bar.density_kg_per_m3 < 0.0)
    fail("rebar of region " + name + " in quad " + std::to_string(q) +
         " needs a layer tangent, thickness, spacing and Young's modulus");
  const Eigen::Vector2d tn = t.normalized();
  d.a0 = Eigen::Vector3d(std::cos(bar.angle_rad) * tn[0], std::cos(bar.angle_rad) * tn[1],
                         std::sin(bar.angle_rad));
  d.volume_fraction = bar.area_m2 / (bar.spacing_m * thickness);
  d.fibre_modulus_Pa = d.volume_fraction * bar.youngs_modulus_Pa;
  density += d.volume_fraction * bar.density_kg_per_m3;
}

// Quad q's reference geometry, material and rebar; `density` is set to its
// density with the bars [kg/m^3], and lo..hi grows to hold its nodes.
QuadData make_quad(const CrossSection& s, const TyreMaterials& m, std::size_t q, double& density,
                   Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
  const std::size_t n_nodes = s.nodes.size();
  const int region = static_cast<int>(s.quad_region[q]);
  if (region < 0 || region >= kRegionCount) fail("quad " + std::to_string(q) + " has no region");
  const std::string name = region_name(s.quad_region[q]);
  QuadData d{};
  d.nodes = s.quads[q];
  double X[4][2];
  for (int i = 0; i < 4; ++i) {
    check_node(d.nodes[i], n_nodes, "quads");
    X[i][0] = s.nodes[d.nodes[i]][0];
    X[i][1] = s.nodes[d.nodes[i]][1];
    lo = lo.cwiseMin(s.nodes[d.nodes[i]]);
    hi = hi.cwiseMax(s.nodes[d.nodes[i]]);
  }
  d.ref = quad4axi_reference(X);
  d.solid = &m.solid[region];
  d.shear_modulus_Pa = d.solid->shear_modulus_Pa();
  density = d.solid->density_kg_per_m3();
  const double bulk = d.solid->bulk_modulus_Pa();
  if (!(density > 0.0) || !(d.shear_modulus_Pa > 0.0) || !(bulk > 0.0))
    fail("region " + name + " needs positive density, shear and bulk moduli");

  const RebarLayer& bar = m.rebar[region];
  if (bar.area_m2 > 0.0) set_quad_rebar(s, bar, q, name, d, density);
  return d;
}

// After the quads: every node in a quad, the twist held on the axis and on the
// listed nodes, y held on the listed nodes, the liner's edges valid.
void hold_remaining_dofs(const CrossSection& s, const AxisymLoadCase& load, const std::vector<double>& node_mass,
                         std::vector<char>& fixed) {
  const std::size_t n_nodes = s.nodes.size();
  for (std::size_t i = 0; i < n_nodes; ++i) {
    if (!(node_mass[i] > 0.0)) fail("node " + std::to_string(i) + " belongs to no quad");
    // On the axis the twist is meaningless (no hoop displacement) and has no inertia.
    if (!(s.nodes[i][0] > 0.0)) fixed[kDofsPerNode * i + 2] = 1;
  }
  for (const auto& e : s.inner_liner_edges)
    if (e[0] < 0 || static_cast<std::size_t>(e[0]) >= s.quads.size() || e[1] < 0 || e[1] > 3)
      fail("inner_liner_edges has an invalid (quad, edge) pair");

  for (int node : load.fixed_y_nodes) {
    check_node(node, n_nodes, "fixed_y_nodes");
    fixed[kDofsPerNode * node + 1] = 1;
  }
  for (int node : load.fixed_twist_nodes) {
    check_node(node, n_nodes, "fixed_twist_nodes");
    fixed[kDofsPerNode * node + 2] = 1;
  }
}

// The per-dof mass, its inverse and the residual weight (see Model).
void set_dof_masses(const CrossSection& s, const std::vector<double>& node_mass, const std::vector<char>& fixed,
                    Model& model) {
  const std::size_t n_nodes = s.nodes.size();
  model.mass.resize(kDofsPerNode * n_nodes);
  model.inverse_mass.resize(kDofsPerNode * n_nodes);
  model.residual_weight.resize(kDofsPerNode * n_nodes);
  for (std::size_t i = 0; i < n_nodes; ++i) {
    const double R = s.nodes[i][0];
    for (int c = 0; c < kDofsPerNode; ++c) {
      const std::size_t k = kDofsPerNode * i + c;
      model.mass[k] = c < 2 ? node_mass[i] : node_mass[i] * R * R;
      model.inverse_mass[k] = fixed[k] ? 0.0 : 1.0 / model.mass[k];
      model.residual_weight[k] = fixed[k] ? 0.0 : c < 2 ? 1.0 : 1.0 / (R * R);
    }
  }
}

Model build_model(const CrossSection& s, const TyreMaterials& m, const AxisymLoadCase& load) {
  const std::size_t n_nodes = s.nodes.size();
  if (s.quad_region.size() != s.quads.size()) fail("quad_region size differs from quads");
  Model model;
  std::vector<double> node_mass(n_nodes, 0.0);  // kg per radian
  std::vector<char> fixed = held_dofs(s, load);
  model.quads.reserve(s.quads.size());
  double min_step = HUGE_VAL, min_shear_speed = HUGE_VAL;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(HUGE_VAL), hi = -lo;
  for (std::size_t q = 0; q < s.quads.size(); ++q) {
    double density = 0.0;
    const QuadData d = make_quad(s, m, q, density, lo, hi);
    double step = quad4axi_stable_time_step_s(d.ref, density, d.solid->bulk_modulus_Pa(), d.shear_modulus_Pa,
                                              m.hourglass_coefficient, d.fibre_modulus_Pa);
    if (step < load.mass_scaling_time_step_s) {  // omega^2 ~ 1/rho
      density *= (load.mass_scaling_time_step_s / step) * (load.mass_scaling_time_step_s / step);
      step = load.mass_scaling_time_step_s;
    }
    // A quad whose nodes are all held (e.g. the bead tied to the rim) never deforms:
    // it sets no step.
    bool all_held = true;
    for (int i = 0; i < 4; ++i) all_held = all_held && fixed[kDofsPerNode * d.nodes[i]];
    if (!all_held) {
      min_step = std::min(min_step, step);
      min_shear_speed = std::min(min_shear_speed, std::sqrt(d.shear_modulus_Pa / density));
    }
    for (int i = 0; i < 4; ++i) node_mass[d.nodes[i]] += 0.25 * density * d.ref.volume_per_rad_m3;
    model.quads.push_back(d);
  }
  if (model.quads.empty()) fail("the cross-section has no quads");
  hold_remaining_dofs(s, load, node_mass, fixed);
  set_dof_masses(s, node_mass, fixed, model);
  model.time_step_s = kSafetyFactor * min_step;
  model.ramp_time_s = load.ramp_time_s > 0.0
                          ? load.ramp_time_s
                          : 2.0 * (hi - lo).maxCoeff() / min_shear_speed;
  return model;
}

// Internal forces, moments, energies and (optionally) stresses of one quad at the
// state q (r, y, phi per node).
void evaluate_quad(const QuadData& d, const std::vector<double>& q, double hourglass_coefficient,
                   QuadState& out, Eigen::Matrix3d* cauchy = nullptr, double* log_strain = nullptr) {
  double xe[4][2], twist[4];
  for (int i = 0; i < 4; ++i) {
    const double* node = &q[kDofsPerNode * d.nodes[i]];
    xe[i][0] = node[0];
    xe[i][1] = node[1];
    twist[i] = node[2];
  }
  const Eigen::Matrix3d F = quad4axi_deformation_gradient(d.ref, xe, twist);
  double energy = 0.0;
  Eigen::Matrix3d tau = kirchhoff_stress(*d.solid, F, &energy);
  if (d.volume_fraction > 0.0) {
    energy += add_rebar_kirchhoff_stress(d.a0, d.volume_fraction,
                                         d.fibre_modulus_Pa / d.volume_fraction, F, tau);
    if (log_strain) *log_strain = std::log((F * d.a0).norm());
  } else if (log_strain) {
    *log_strain = 0.0;
  }
  out.strain_energy = energy * d.ref.volume_per_rad_m3;
  out.hourglass_energy = quad4axi_internal_forces(d.ref, xe, twist, F, tau, hourglass_coefficient,
                                                  d.shear_modulus_Pa, out.f, out.moment);
  if (cauchy) *cauchy = tau / F.determinant();
}

// Follower pressure: traction -p n on the deformed edge a -> b of a counter-clockwise
// quad, n L = (dy, -dr) the outward normal times the length; integrating the linear
// shape functions against the axisymmetric measure r ds gives the weights
// (r_a/3 + r_b/6) and (r_a/6 + r_b/3). The twist changes neither: with
// x = r e_r(Theta + phi) + y e_y on the surface, dx/ds = r' e_r + y' e_y + r phi' e_theta
// and dx/dTheta = r e_theta, so the area vector dx/ds x dx/dTheta has no theta component
// and does not depend on phi.
void add_pressure(const CrossSection& s, const std::vector<double>& q, double p,
                  std::vector<double>& f_ext) {
  for (const auto& e : s.inner_liner_edges) {
    const auto& quad = s.quads[e[0]];
    const int a = quad[e[1]], b = quad[(e[1] + 1) % 4];
    const double ra = q[kDofsPerNode * a], ya = q[kDofsPerNode * a + 1];
    const double rb = q[kDofsPerNode * b], yb = q[kDofsPerNode * b + 1];
    const double dr = rb - ra, dy = yb - ya;
    const double wa = ra / 3.0 + rb / 6.0, wb = ra / 6.0 + rb / 3.0;
    f_ext[kDofsPerNode * a] -= p * dy * wa;
    f_ext[kDofsPerNode * a + 1] += p * dr * wa;
    f_ext[kDofsPerNode * b] -= p * dy * wb;
    f_ext[kDofsPerNode * b + 1] += p * dr * wb;
  }
}

// The reference state (R, Y, 0) per node.
std::vector<double> reference_state(const CrossSection& section) {
  const std::size_t n_nodes = section.nodes.size();
  std::vector<double> q0(kDofsPerNode * n_nodes, 0.0);
  for (std::size_t n = 0; n < n_nodes; ++n) {
    q0[kDofsPerNode * n] = section.nodes[n][0];
    q0[kDofsPerNode * n + 1] = section.nodes[n][1];
  }
  return q0;
}

// The internal forces f_int (moments M_i on the twist dofs) at the state q, and
// the strain and hourglass energies (per radian).
void internal_forces(const Model& model, const std::vector<double>& q, double hg, std::vector<QuadState>& states,
                     std::vector<double>& f_int, double& strain_energy, double& hourglass_energy) {
  // Serial on purpose: a cross-section has ~1e2-1e3 quads (~0.1 us each), less work
  // per step than an OpenMP fork/join costs (measured 8x slower on 2 threads with
  // 120 quads). The result is therefore independent of the thread count.
  for (std::size_t e = 0; e < model.quads.size(); ++e) evaluate_quad(model.quads[e], q, hg, states[e]);
  std::fill(f_int.begin(), f_int.end(), 0.0);
  strain_energy = 0.0;
  hourglass_energy = 0.0;
  for (std::size_t e = 0; e < model.quads.size(); ++e) {
    const auto& nodes = model.quads[e].nodes;
    for (int i = 0; i < 4; ++i) {
      double* fn = &f_int[kDofsPerNode * nodes[i]];
      fn[0] += states[e].f[i][0];
      fn[1] += states[e].f[i][1];
      fn[2] += states[e].moment[i];
    }
    strain_energy += states[e].strain_energy;
    hourglass_energy += states[e].hourglass_energy;
  }
}

// The sums that decide convergence, over every dof.
struct StepMeasures {
  double residual_sq = 0.0, load_sq = 0.0, work = 0.0, kinetic = 0.0;
};

StepMeasures measure_step(const Model& model, const std::vector<double>& q, const std::vector<double>& q0,
                          const std::vector<double>& v, const std::vector<double>& f_int,
                          const std::vector<double>& f_ext) {
  // Twist dofs as hoop displacements R phi: force M / R, mass m (see axisym.hpp).
  // Held dofs never move (u = 0, v = 0) and have weight 0.
  double residual_sq = 0.0, load_sq = 0.0, work = 0.0, kinetic = 0.0;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const double r = f_ext[k] - f_int[k];
    load_sq += f_ext[k] * f_ext[k];
    residual_sq += model.residual_weight[k] * r * r;
    work += f_ext[k] * (q[k] - q0[k]);
    kinetic += 0.5 * model.mass[k] * v[k] * v[k];
  }
  return {residual_sq, load_sq, work, kinetic};
}

// Kinetic damping: restart from rest once the kinetic energy has passed a peak;
// then one central-difference step, v at half steps.
void advance(const Model& model, double kinetic, double& previous_kinetic, const std::vector<double>& f_int,
             const std::vector<double>& f_ext, std::vector<double>& v, std::vector<double>& q) {
  const double dt = model.time_step_s;
  if (kinetic < previous_kinetic) {
    std::fill(v.begin(), v.end(), 0.0);
    previous_kinetic = 0.0;
  } else {
    previous_kinetic = kinetic;
  }
  for (std::size_t k = 0; k < q.size(); ++k) {  // central difference, v at half steps
    v[k] += dt * (f_ext[k] - f_int[k]) * model.inverse_mass[k];
    q[k] += dt * v[k];
  }
}

// The nodes, twists, stresses and bar strains of the final state q.
void write_final_state(const Model& model, const std::vector<double>& q, double hg, AxisymResult& result) {
  const std::size_t n_nodes = q.size() / kDofsPerNode;
  result.nodes.resize(n_nodes);
  result.twist_rad.resize(n_nodes);
  for (std::size_t n = 0; n < n_nodes; ++n) {
    result.nodes[n] = Eigen::Vector2d(q[kDofsPerNode * n], q[kDofsPerNode * n + 1]);
    result.twist_rad[n] = q[kDofsPerNode * n + 2];
  }
  result.quad_stress_Pa.resize(model.quads.size());
  result.quad_rebar_log_strain.resize(model.quads.size());
  for (std::size_t e = 0; e < model.quads.size(); ++e) {
    QuadState state;
    evaluate_quad(model.quads[e], q, hg, state, &result.quad_stress_Pa[e],
                  &result.quad_rebar_log_strain[e]);
  }
}

}  // namespace

AxisymResult solve_axisym(const CrossSection& section, const TyreMaterials& materials,
                          const AxisymLoadCase& load,
                          const std::function<void(long, double)>& progress) {
  const Model model = build_model(section, materials, load);
  const std::size_t n_dofs = kDofsPerNode * section.nodes.size();
  const double dt = model.time_step_s;
  const double hg = materials.hourglass_coefficient;

  const std::vector<double> q0 = reference_state(section);
  std::vector<double> q = q0;
  // v: velocities (r, y) and twist rates [rad/s] at half steps; f_int holds the
  // moments M_i on the twist dofs.
  std::vector<double> v(n_dofs, 0.0), f_int(n_dofs), f_ext(n_dofs);
  std::vector<QuadState> states(model.quads.size());
  AxisymResult result;
  result.time_step_s = dt;
  double previous_kinetic = 0.0;

  for (long step = 0;; ++step) {
    const double t = step * dt;
    const double load_factor =
        t >= model.ramp_time_s ? 1.0 : 0.5 * (1.0 - std::cos(kPi * t / model.ramp_time_s));
    double strain_energy = 0.0, hourglass_energy = 0.0;
    internal_forces(model, q, hg, states, f_int, strain_energy, hourglass_energy);
    std::fill(f_ext.begin(), f_ext.end(), 0.0);
    add_pressure(section, q, load.pressure_Pa * load_factor, f_ext);
    const StepMeasures s = measure_step(model, q, q0, v, f_int, f_ext);
    if (!std::isfinite(s.residual_sq) || !std::isfinite(strain_energy))
      fail("diverged at step " + std::to_string(step) + " (inverted element or unstable step)");
    result.residual_ratio = s.load_sq > 0.0 ? std::sqrt(s.residual_sq / s.load_sq) : 0.0;
    result.kinetic_energy_J_per_rad = s.kinetic;
    result.strain_energy_J_per_rad = strain_energy;
    result.hourglass_energy_J_per_rad = hourglass_energy;
    result.steps = step;
    const bool held = t >= model.ramp_time_s;
    if (held && result.residual_ratio <= load.tolerance &&
        s.kinetic <= load.tolerance * 0.5 * std::abs(s.work)) {
      result.converged = true;
      break;
    }
    if (load.pressure_Pa == 0.0 && s.residual_sq == 0.0) {  // nothing loads the section
      result.converged = true;
      break;
    }
    if (step >= load.max_steps) break;
    if (progress && step % kProgressInterval == 0) progress(step, result.residual_ratio);
    advance(model, s.kinetic, previous_kinetic, f_int, f_ext, v, q);
  }
  write_final_state(model, q, hg, result);
  return result;
}

}  // namespace tyre_fe
