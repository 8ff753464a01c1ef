#include "tyre_fe/solver3d.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <omp.h>

#include "cosim/coupling_window.hpp"
#include "cosim/error.hpp"
#include "cosim/parallel.hpp"
#include "cosim/penalty_contact.hpp"
#include "cosim/quad_facet.hpp"

namespace tyre_fe {

double Energies::balance_J() const {
  return kinetic_J + internal_J - initial_J - external_work_J - damping_work_J - contact_work_J;
}

double Energies::balance_error() const {
  const double scale = std::max({std::fabs(internal_J), kinetic_J, std::fabs(external_work_J), 1e-30});
  return std::fabs(balance_J()) / scale;
}

State3d make_state3d(const Model3d& model, const std::vector<Eigen::Vector3d>& current,
                     double rim_mass_kg, double rim_inertia_kg_m2) {
  State3d s;
  const std::size_t nn = current.size();
  s.x.resize(nn), s.y.resize(nn), s.z.resize(nn);
  for (std::size_t i = 0; i < nn; ++i) s.x[i] = current[i].x(), s.y[i] = current[i].y(), s.z[i] = current[i].z();
  s.vx.assign(nn, 0.0), s.vy.assign(nn, 0.0), s.vz.assign(nn, 0.0);
  s.fx.assign(nn, 0.0), s.fy.assign(nn, 0.0), s.fz.assign(nn, 0.0);
  s.pressure_fx.assign(nn, 0.0), s.pressure_fy.assign(nn, 0.0), s.pressure_fz.assign(nn, 0.0);
  s.contact_fx.assign(nn, 0.0), s.contact_fy.assign(nn, 0.0), s.contact_fz.assign(nn, 0.0);
  s.element_force.assign(model.hex_batches.force_array_size(), 0.0);
  s.element_energy.assign(model.mesh.hexes.size(), 0.0);
  s.element_viscous_power.assign(model.mesh.hexes.size(), 0.0);
  s.element_hourglass.assign(model.mesh.hexes.size(), 0.0);
  s.rim_nodes = model.mesh.rim_nodes;
  s.rim_node_v_old.assign(3 * s.rim_nodes.size(), 0.0);
  s.rim.mass_kg = rim_mass_kg;
  s.rim.inertia_kg_m2 = rim_inertia_kg_m2;
  for (int n : s.rim_nodes) {
    s.rim_offset.push_back(s.x[n]);
    s.rim_offset.push_back(s.z[n]);
    s.rim.mass_kg += model.node_mass_kg[n];
    s.rim.inertia_kg_m2 += model.node_mass_kg[n] * (s.x[n] * s.x[n] + s.z[n] * s.z[n]);
  }
  s.dt_s = model.stable_dt_s;
  s.road.anchor_x.assign(model.contact_nodes.size(), 0.0);
  s.road.anchor_y.assign(model.contact_nodes.size(), 0.0);
  s.road.in_contact.assign(model.contact_nodes.size(), 0);
  s.road.normal_force_N.assign(model.contact_nodes.size(), 0.0);
  return s;
}

void place_road(const Model3d& model, State3d& s, double gap_m, double friction_coefficient,
                double penalty_scale) {
  set_road(s, lowest_contact_z(model, s) - gap_m, friction_coefficient, penalty_scale);
}

double lowest_contact_z(const Model3d& model, const State3d& s) {
  double lowest = 1e30;
  for (int n : model.contact_nodes) lowest = std::min(lowest, s.z[n]);
  return lowest;
}

void set_road(State3d& s, double height_m, double friction_coefficient, double penalty_scale) {
  s.road.present = true;
  s.road.height_m = height_m;
  s.road.friction_coefficient = friction_coefficient;
  s.road.penalty_scale = penalty_scale > 0.0 ? penalty_scale : 0.1;
}

void zero_velocities(State3d& s) {
  // The kinetic energy removed is dissipation, so the energy balance still closes.
  s.energy.damping_work_J -= s.energy.kinetic_J;
  s.energy.kinetic_J = 0.0;
  std::fill(s.vx.begin(), s.vx.end(), 0.0);
  std::fill(s.vy.begin(), s.vy.end(), 0.0);
  std::fill(s.vz.begin(), s.vz.end(), 0.0);
  s.rim.vx = s.rim.vz = s.rim.omega = 0.0;
}

double radial_position(const State3d& s, int node) {
  return std::hypot(s.x[node] - s.rim.x, s.z[node] - s.rim.z);
}

namespace {

// Stage 1: per-element forces (Kirchhoff stress of rubber/steel + rebar + linear bulk
// viscosity, Abaqus/Explicit 6.3.3), a batch of elements at a time (hex8_batch.hpp),
// written per element; no scatter.
void element_forces(const Model3d& m, State3d& s) {
  const double* const position[3] = {s.x.data(), s.y.data(), s.z.data()};
  const double* const velocity[3] = {s.vx.data(), s.vy.data(), s.vz.data()};
  const bool viscous = m.options.bulk_viscosity_linear > 0.0;
  const Hex8ElementResults results{s.element_energy.data(), s.element_hourglass.data(),
                                   s.element_viscous_power.data()};
  const auto& batches = m.hex_batches.batches;
  cosim::parallel_for("tyre element forces", batches.size(), [&](std::size_t b) {
    if (b + 2 < batches.size()) prefetch_hex8_batch(batches[b + 2]);
    hex8_batch_forces(batches[b], position, velocity, viscous, &s.element_force[b * 24 * kHexLanes], results);
  });
}

// Stage 2: nodal force = minus the sum of the element internal forces (gather).
void gather_forces(const Model3d& m, State3d& s) {
  cosim::parallel_for("tyre gather", s.x.size(), [&](std::size_t i) {
    double f[3] = {0.0, 0.0, 0.0};
    for (int k = m.node_hex_begin[i]; k < m.node_hex_begin[i + 1]; ++k) {
      const double* fe = &s.element_force[static_cast<std::size_t>(m.node_hex_entries[k])];
      f[0] -= fe[0], f[1] -= fe[kHexLanes], f[2] -= fe[2 * kHexLanes];
    }
    s.fx[i] = f[0], s.fy[i] = f[1], s.fz[i] = f[2];
  });
}

// Stage 3: inflation pressure, a follower load on the current inner-liner facets,
// pushing the liner away from the cavity (the facet normal points into the cavity).
void pressure_forces(const Model3d& m, State3d& s) {
  std::fill(s.pressure_fx.begin(), s.pressure_fx.end(), 0.0);
  std::fill(s.pressure_fy.begin(), s.pressure_fy.end(), 0.0);
  std::fill(s.pressure_fz.begin(), s.pressure_fz.end(), 0.0);
  if (s.pressure_Pa == 0.0) return;
  for (int fi : m.pressure_facets) {
    const auto& n = m.mesh.facets[fi].nodes;
    const Eigen::Vector3d d1(s.x[n[2]] - s.x[n[0]], s.y[n[2]] - s.y[n[0]], s.z[n[2]] - s.z[n[0]]);
    const Eigen::Vector3d d2(s.x[n[3]] - s.x[n[1]], s.y[n[3]] - s.y[n[1]], s.z[n[3]] - s.z[n[1]]);
    const Eigen::Vector3d f = -0.25 * s.pressure_Pa * cosim::quad_area_vector_from_diagonals(d1, d2);  // -p A / 4 per node
    for (int a : n) {
      s.fx[a] += f.x(), s.fy[a] += f.y(), s.fz[a] += f.z();
      s.pressure_fx[a] += f.x(), s.pressure_fy[a] += f.y(), s.pressure_fz[a] += f.z();
    }
  }
}

// The road's normal damper, a fraction of critical while approaching.
constexpr double kRoadDampingRatio = 0.1;

// Stage 4: road contact, node to plane. Normal: penalty k = scale m / dt^2 with 10 %
// of critical damping while approaching. Friction: an elastic stick spring of the
// same stiffness anchored where the node stuck, capped at mu f_n (Coulomb slip moves
// the anchor): sticking nodes do not creep, which the rolling radius needs.
void road_contact(const Model3d& m, State3d& s) {
  RoadState& r = s.road;
  r.force_x_N = r.force_y_N = r.force_z_N = r.contact_area_m2 = 0.0;
  if (!r.present) return;
  const double dt2 = s.dt_s * s.dt_s;
  for (std::size_t c = 0; c < m.contact_nodes.size(); ++c) {
    const int i = m.contact_nodes[c];
    const double g = r.height_m - s.z[i];
    if (g <= 0.0) {
      r.in_contact[c] = 0;
      r.normal_force_N[c] = 0.0;
      continue;
    }
    const double mass = m.node_mass_kg[i];
    const double k = r.penalty_scale * mass / dt2;
    const double damper = cosim::penalty::damping_coefficient(kRoadDampingRatio, k, mass);
    const double fn = cosim::penalty::normal_force(k, g, s.vz[i], damper, cosim::penalty::Damping::approach_only).force_N;
    if (!r.in_contact[c]) r.anchor_x[c] = s.x[i], r.anchor_y[c] = s.y[i], r.in_contact[c] = 1;
    double ftx = -k * (s.x[i] - r.anchor_x[c]), fty = -k * (s.y[i] - r.anchor_y[c]);
    const double ft = std::hypot(ftx, fty), limit = r.friction_coefficient * fn;
    const cosim::penalty::CoulombCap cone = cosim::penalty::coulomb_cap(ft, limit);
    if (cone.sliding) {
      ftx *= cone.scale, fty *= cone.scale;
      r.anchor_x[c] = s.x[i] + ftx / k, r.anchor_y[c] = s.y[i] + fty / k;
    }
    s.fx[i] += ftx, s.fy[i] += fty, s.fz[i] += fn;
    s.contact_fx[i] += ftx, s.contact_fy[i] += fty, s.contact_fz[i] += fn;
    r.force_x_N += ftx, r.force_y_N += fty, r.force_z_N += fn;
    r.normal_force_N[c] = fn;
    r.contact_area_m2 += m.contact_node_area_m2[c];
  }
}

// Stage 5: rim rigid body (free nodes are updated in stage 6).
// Returns the power of the rim loads and of the reactions of prescribed motion.
double rim_update(const Model3d& /*model*/, State3d& s, const RimDrive& d) {
  RimState& rim = s.rim;
  double fx = 0.0, fz = 0.0, my = 0.0;
  for (std::size_t k = 0; k < s.rim_nodes.size(); ++k) {
    const int n = s.rim_nodes[k];
    const double rx = s.x[n] - rim.x, rz = s.z[n] - rim.z;
    fx += s.fx[n], fz += s.fz[n];
    my += rz * s.fx[n] - rx * s.fz[n];
  }
  rim.tyre_force_x_N = fx, rim.tyre_force_z_N = fz, rim.tyre_moment_y_Nm = my;
  rim.rm2_Nm = -my;
  rim.applied_torque_Nm = d.spin_prescribed ? 0.0 : d.drive_torque_Nm;
  rim.wheel_load_N = d.wheel_load_N;
  const double dt = s.dt_s;
  double power = 0.0;
  // x: held or prescribed; the reaction does work.
  const double vx_new = d.hold_x ? 0.0 : d.forward_speed_m_per_s;
  power += (rim.mass_kg * (vx_new - rim.vx) / dt - fx) * 0.5 * (vx_new + rim.vx);
  rim.vx = vx_new;
  // z: free under the wheel load (with the relaxation damping), held or prescribed;
  // the reaction of a held or prescribed motion does work, as in x.
  const double vz_old = rim.vz;
  if (d.hold_z || d.prescribe_vz) {
    rim.vz = d.prescribe_vz ? d.vertical_speed_m_per_s : 0.0;
    power += (rim.mass_kg * (rim.vz - vz_old) / dt - fz + d.wheel_load_N) * 0.5 * (rim.vz + vz_old);
  } else {
    const double damping = -s.damping_per_s * rim.mass_kg * rim.vz;
    rim.vz += dt * (fz - d.wheel_load_N + damping) / rim.mass_kg;
    s.energy.damping_work_J += damping * 0.5 * (rim.vz + vz_old) * dt;
  }
  power += -d.wheel_load_N * 0.5 * (rim.vz + vz_old);
  // spin about y: prescribed or driven by a torque.
  const double w_old = rim.omega;
  if (d.spin_prescribed) {
    rim.omega = d.angular_velocity_rad_per_s;
    power += (rim.inertia_kg_m2 * (rim.omega - w_old) / dt - my) * 0.5 * (rim.omega + w_old);
  } else {
    rim.omega += dt * (my + d.drive_torque_Nm) / rim.inertia_kg_m2;
    power += d.drive_torque_Nm * 0.5 * (rim.omega + w_old);
  }
  rim.x += dt * rim.vx, rim.z += dt * rim.vz, rim.angle += dt * rim.omega;
  const double c = std::cos(rim.angle), sn = std::sin(rim.angle);
  for (std::size_t k = 0; k < s.rim_nodes.size(); ++k) {
    const int n = s.rim_nodes[k];
    const double dx = s.rim_offset[2 * k], dz = s.rim_offset[2 * k + 1];
    const double rx = dx * c + dz * sn, rz = -dx * sn + dz * c;  // R_y(angle) d
    s.x[n] = rim.x + rx, s.z[n] = rim.z + rz;
    s.vx[n] = rim.vx + rim.omega * rz, s.vz[n] = rim.vz - rim.omega * rx, s.vy[n] = 0.0;
  }
  return power;
}

}  // namespace

void commit_window_impulse(TerrainCoupling& t) {
  for (int c = 0; c < 3; ++c) t.impulse_Ns[c] += t.window_impulse_Ns[c], t.window_impulse_Ns[c] = 0.0;
}

void add_terrain_loads(State3d& s) {
  TerrainCoupling& t = s.terrain;
  const cosim::SurfaceLoads& l = t.loads;
  for (std::size_t k = 0; k < l.nodes.size(); ++k) {
    const int i = t.surface.node_ids[l.nodes[k]];
    s.fx[i] += l.fx_N[k], s.fy[i] += l.fy_N[k], s.fz[i] += l.fz_N[k];
    s.contact_fx[i] += l.fx_N[k], s.contact_fy[i] += l.fy_N[k], s.contact_fz[i] += l.fz_N[k];
  }
  const auto& total = t.load_totals.force_N;
  t.window_impulse_Ns[0] += s.dt_s * total[0], t.window_impulse_Ns[1] += s.dt_s * total[1];
  t.window_impulse_Ns[2] += s.dt_s * total[2];
  if (++t.substep == t.substeps) t.substep = 0, ++t.exchange;
}

void compute_forces(const Model3d& m, State3d& s) {
  const double t0 = s.time_stages ? omp_get_wtime() : 0.0;
  element_forces(m, s);
  gather_forces(m, s);
  const double t1 = s.time_stages ? omp_get_wtime() : 0.0;
  pressure_forces(m, s);
  const double t2 = s.time_stages ? omp_get_wtime() : 0.0;
  std::fill(s.contact_fx.begin(), s.contact_fx.end(), 0.0);
  std::fill(s.contact_fy.begin(), s.contact_fy.end(), 0.0);
  std::fill(s.contact_fz.begin(), s.contact_fz.end(), 0.0);
  road_contact(m, s);
  if (s.time_stages) {
    const double t3 = omp_get_wtime();
    s.stage_times.internal_forces_s += t1 - t0;
    s.stage_times.rest_s += t2 - t1;
    s.stage_times.contact_s += t3 - t2;
  }
}

bool step3d(const Model3d& m, State3d& s, const RimDrive& drive) {
  compute_forces(m, s);
  return integrate(m, s, drive);
}

double connect_to_terrain(TerrainPort& port, State3d& s) {
  const double window = port.connect(s.terrain.surface, s.dt_s, s.terrain.exchange, s.time_s);
  s.terrain.substeps = cosim::substeps_per_window(window, s.dt_s);
  s.dt_s = window / s.terrain.substeps;
  return window;
}

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

void send_surface(State3d& s, TerrainPort& port, double& exchange_s) {
  TerrainCoupling& terrain = s.terrain;
  const auto t0 = std::chrono::steady_clock::now();
  // A splash above the scene's band must meet the tread it flies at, not
  // pass through a part of the surface the terrain was never sent.
  const double band = std::max(terrain.band_m, terrain.loads.particle_reach_z_m);
  terrain.highest_band_m = std::max(terrain.highest_band_m, band);
  surface_near_terrain(terrain.surface, s, band, terrain.sent);
  port.send(terrain.sent, s.rim);
  commit_window_impulse(terrain);
  exchange_s += seconds_since(t0);
}

void receive_loads(State3d& s, TerrainPort& port, double& exchange_s) {
  TerrainCoupling& terrain = s.terrain;
  const auto t0 = std::chrono::steady_clock::now();
  port.receive(terrain.exchange, terrain.loads);
  terrain.load_totals = cosim::totals(terrain.loads);
  exchange_s += seconds_since(t0);
}

void exchange_with_terrain(const Model3d& m, State3d& s, TerrainPort& port, double& exchange_s) {
  send_surface(s, port, exchange_s);
  compute_forces(m, s);  // while the terrain works on the surface
  receive_loads(s, port, exchange_s);
}

void complete_step_on_terrain(const Model3d& m, State3d& s, const RimDrive& drive, bool forces_computed) {
  if (!forces_computed) compute_forces(m, s);
  add_terrain_loads(s);
  if (!integrate(m, s, drive))
    throw cosim::Error(non_finite_message(m, s));
}

// The failure message of a step that went non-finite: the first element whose
// energy is not finite (an inverted element; where it is on the undeformed
// tyre, its current nodes being lost) or node whose position is not, and the
// largest contact load on a node in that step, with its node's mass (a load the
// node cannot carry over the step shows here).
std::string non_finite_message(const Model3d& m, const State3d& s) {
  // Positions to the micrometre: a node on a plane of symmetry reads y = 0, not its round-off.
  auto text = [](double x, double y, double z) {
    auto um = [](double v) { return cosim::number_text(std::round(v * 1e6) / 1e6 + 0.0); };  // + 0: no "-0"
    return "(" + um(x) + ", " + um(y) + ", " + um(z) + ") m";
  };
  std::string where;
  for (std::size_t e = 0; e < s.element_energy.size() && where.empty(); ++e)
    if (!std::isfinite(s.element_energy[e])) {
      const Eigen::Vector3d& X = m.mesh.nodes[m.mesh.hexes[e][0]];
      where = "element " + std::to_string(e) + " (its first node at " + text(X[0], X[1], X[2]) +
              " on the undeformed tyre) has a non-finite energy";
    }
  for (std::size_t i = 0; i < s.x.size() && where.empty(); ++i)
    if (!std::isfinite(s.x[i] + s.y[i] + s.z[i])) where = "node " + std::to_string(i) + " has a non-finite position";
  if (where.empty()) where = "the energies are not finite";
  double largest = 0.0;
  std::size_t at_node = 0;
  for (std::size_t i = 0; i < s.contact_fx.size(); ++i) {
    const double f = std::sqrt(s.contact_fx[i] * s.contact_fx[i] + s.contact_fy[i] * s.contact_fy[i] +
                               s.contact_fz[i] * s.contact_fz[i]);
    if (f > largest) largest = f, at_node = i;
  }
  if (largest > 0.0)
    where += "; the largest contact load was " + cosim::number_text(largest) + " N on node " +
             std::to_string(at_node) + " (mass " + cosim::number_text(m.node_mass_kg[at_node]) + " kg) at " +
             text(s.x[at_node], s.y[at_node], s.z[at_node]);
  return "non-finite state at t = " + cosim::number_text(s.time_s) + " s (step " + std::to_string(s.step) + "): " +
         where;
}

bool integrate(const Model3d& m, State3d& s, const RimDrive& drive) {
  const double dt = s.dt_s;
  const double t3b = s.time_stages ? omp_get_wtime() : 0.0;
  // Mass-proportional damping on the free nodes (dynamic relaxation).
  double damping_power = 0.0;
  for (double p : s.element_viscous_power) damping_power += p;
  const double bulk_viscous_power = damping_power;
  if (s.damping_per_s > 0.0) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (m.is_rim_node[i]) continue;
      const double c = s.damping_per_s * m.node_mass_kg[i];
      const double gx = -c * s.vx[i], gy = -c * s.vy[i], gz = -c * s.vz[i];
      s.fx[i] += gx, s.fy[i] += gy, s.fz[i] += gz;
    }
  }
  for (std::size_t k = 0; k < s.rim_nodes.size(); ++k) {
    const int n = s.rim_nodes[k];
    s.rim_node_v_old[3 * k] = s.vx[n], s.rim_node_v_old[3 * k + 1] = s.vy[n], s.rim_node_v_old[3 * k + 2] = s.vz[n];
  }
  const double rim_power = rim_update(m, s, drive);
  // The work of the pressure, contact and damping forces over the step is their value
  // at t times the velocity at t, the mean of the half-step velocities (central
  // difference: x(t+dt) - x(t-dt) = 2 dt v(t)). With the velocity at t - dt/2 alone the
  // booked work lags by f . a dt^2 / 2 per step; on a rolling tyre the pressure on the
  // liner (outward) meets its centripetal acceleration (inward) on every step, which
  // booked about p V omega^2 dt of work per second that was never done: an apparent loss
  // growing with the distance rolled.
  double pressure_power = 0.0, contact_power = 0.0;
  for (std::size_t k = 0; k < s.rim_nodes.size(); ++k) {
    const int n = s.rim_nodes[k];
    const double mx = 0.5 * (s.rim_node_v_old[3 * k] + s.vx[n]), my = 0.5 * (s.rim_node_v_old[3 * k + 1] + s.vy[n]),
                 mz = 0.5 * (s.rim_node_v_old[3 * k + 2] + s.vz[n]);
    pressure_power += s.pressure_fx[n] * mx + s.pressure_fy[n] * my + s.pressure_fz[n] * mz;
    contact_power += s.contact_fx[n] * mx + s.contact_fy[n] * my + s.contact_fz[n] * mz;
  }
  // Stage 6: central difference on the free nodes.
  double kinetic = 0.0;
  bool finite = true;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (m.is_rim_node[i]) continue;
    const double inv_m = 1.0 / m.node_mass_kg[i];
    const double ux = s.vx[i], uy = s.vy[i], uz = s.vz[i];
    s.vx[i] += dt * s.fx[i] * inv_m, s.vy[i] += dt * s.fy[i] * inv_m, s.vz[i] += dt * s.fz[i] * inv_m;
    // kinetic energy at t from the mean of the half-step velocities
    const double mx = 0.5 * (ux + s.vx[i]), my = 0.5 * (uy + s.vy[i]), mz = 0.5 * (uz + s.vz[i]);
    kinetic += 0.5 * m.node_mass_kg[i] * (mx * mx + my * my + mz * mz);
    pressure_power += s.pressure_fx[i] * mx + s.pressure_fy[i] * my + s.pressure_fz[i] * mz;
    contact_power += s.contact_fx[i] * mx + s.contact_fy[i] * my + s.contact_fz[i] * mz;
    if (s.damping_per_s > 0.0) damping_power -= s.damping_per_s * m.node_mass_kg[i] * (ux * mx + uy * my + uz * mz);
    s.x[i] += dt * s.vx[i], s.y[i] += dt * s.vy[i], s.z[i] += dt * s.vz[i];
    finite = finite && std::isfinite(s.x[i] + s.y[i] + s.z[i]);
  }
  kinetic += 0.5 * s.rim.mass_kg * (s.rim.vx * s.rim.vx + s.rim.vz * s.rim.vz) +
             0.5 * s.rim.inertia_kg_m2 * s.rim.omega * s.rim.omega;
  double internal = 0.0, hourglass = 0.0;
  for (std::size_t e = 0; e < s.element_energy.size(); ++e)
    internal += s.element_energy[e], hourglass += s.element_hourglass[e];
  Energies& en = s.energy;
  if (s.step == 0)
    en.initial_J = internal + kinetic, en.initial_internal_J = internal, en.initial_hourglass_J = hourglass;
  en.kinetic_J = kinetic, en.internal_J = internal, en.hourglass_J = hourglass;
  en.external_work_J += dt * (pressure_power + rim_power);
  en.contact_work_J += dt * contact_power;
  en.damping_work_J += dt * damping_power;
  en.pressure_work_J += dt * pressure_power;
  en.bulk_viscous_work_J += dt * bulk_viscous_power;
  s.time_s += dt;
  ++s.step;
  if (s.time_stages) s.stage_times.rest_s += omp_get_wtime() - t3b;
  return finite && std::isfinite(internal);
}

}  // namespace tyre_fe
