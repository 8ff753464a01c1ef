#include "tyre_fe/state_checkpoint.hpp"

#include <string>

#include "cosim/error.hpp"

namespace tyre_fe {
namespace {

// Per-node and per-element arrays, by name; their sizes are the model's.
// Templates, so that saving reads a const state through the same lists.
template <class S> auto arrays(S& s) {
  return std::vector<std::pair<const char*, decltype(&s.x)>>{{"x", &s.x}, {"y", &s.y}, {"z", &s.z}, {"vx", &s.vx}, {"vy", &s.vy}, {"vz", &s.vz},
          {"fx", &s.fx}, {"fy", &s.fy}, {"fz", &s.fz}, {"pressure_fx", &s.pressure_fx},
          {"pressure_fy", &s.pressure_fy}, {"pressure_fz", &s.pressure_fz}, {"contact_fx", &s.contact_fx},
          {"contact_fy", &s.contact_fy}, {"contact_fz", &s.contact_fz}, {"rim_node_v_old", &s.rim_node_v_old},
          {"element_force", &s.element_force}, {"element_energy", &s.element_energy},
          {"element_hourglass", &s.element_hourglass}, {"element_viscous_power", &s.element_viscous_power},
          {"rim_offset", &s.rim_offset}, {"road.anchor_x", &s.road.anchor_x}, {"road.anchor_y", &s.road.anchor_y},
          {"road.normal_force_N", &s.road.normal_force_N}};
}

template <class S> auto scalars(S& s) {
  auto& r = s.rim;
  auto& road = s.road;
  auto& e = s.energy;
  return std::vector<decltype(&s.time_s)>{&r.x, &r.z, &r.angle, &r.vx, &r.vz, &r.omega, &r.mass_kg, &r.inertia_kg_m2, &r.tyre_force_x_N,
          &r.tyre_force_z_N, &r.tyre_moment_y_Nm, &r.rm2_Nm, &r.applied_torque_Nm, &r.wheel_load_N,
          &road.height_m, &road.friction_coefficient, &road.penalty_scale, &road.force_x_N, &road.force_y_N,
          &road.force_z_N, &road.contact_area_m2, &road.friction_dissipation_J,
          &e.kinetic_J, &e.internal_J, &e.hourglass_J, &e.external_work_J, &e.damping_work_J, &e.contact_work_J,
          &e.initial_J, &s.pressure_Pa, &s.damping_per_s, &s.time_s, &s.dt_s};
}

}  // namespace

void save_state(const State3d& s, cosim::CheckpointWriter& out) {
  for (auto& [name, v] : arrays(s)) out.put(std::string("tyre.") + name, *v);
  std::vector<double> values;
  for (const double* v : scalars(s)) values.push_back(*v);
  out.put("tyre.scalars", values);
  out.put("tyre.road.in_contact", std::vector<std::uint8_t>(s.road.in_contact.begin(), s.road.in_contact.end()));
  out.put("tyre.flags", std::vector<std::uint64_t>{s.step, s.road.present ? 1u : 0u});
}

void restore_state(const cosim::CheckpointReader& in, State3d& s) {
  for (auto& [name, v] : arrays(s)) {
    const std::string key = std::string("tyre.") + name;
    // The road's arrays are empty until the road is placed (the loading stage).
    *v = std::string(name).rfind("road.", 0) == 0 ? in.get<double>(key) : in.get<double>(key, v->size());
  }
  const auto values = in.get<double>("tyre.scalars", scalars(s).size());
  std::size_t k = 0;
  for (double* v : scalars(s)) *v = values[k++];
  const auto contact = in.get<std::uint8_t>("tyre.road.in_contact", s.road.anchor_x.size());
  s.road.in_contact.assign(contact.begin(), contact.end());
  const auto flags = in.get<std::uint64_t>("tyre.flags", 2);
  s.step = flags[0], s.road.present = flags[1] != 0;
}

void save_terrain_coupling(const TerrainCoupling& t, double window_s, cosim::CheckpointWriter& out) {
  if (t.substep != 0) throw cosim::Error("a coupled tyre's checkpoint is taken between windows only");
  out.put("coupling.surface_x_m", t.surface.x_m);
  out.put("coupling.surface_y_m", t.surface.y_m);
  out.put("coupling.surface_z_m", t.surface.z_m);
  out.put("coupling.surface_node_mass_kg", t.surface.node_mass_kg);
  out.put("coupling.exchange", std::vector<std::uint64_t>{t.exchange, static_cast<std::uint64_t>(t.substeps)});
  out.put("coupling.doubles",
          std::vector<double>{window_s, t.band_m, t.load_totals.force_N[0], t.load_totals.force_N[1],
                              t.load_totals.force_N[2], t.load_totals.contact_area_m2, t.impulse_Ns[0], t.impulse_Ns[1],
                              t.impulse_Ns[2], t.window_impulse_Ns[0], t.window_impulse_Ns[1], t.window_impulse_Ns[2],
                              t.loads.particle_reach_z_m, t.highest_band_m});
}

double restore_terrain_coupling(const cosim::CheckpointReader& in, TerrainCoupling& t) {
  const std::size_t n = t.surface.node_ids.size();
  t.surface.x_m = in.get<double>("coupling.surface_x_m", n);
  t.surface.y_m = in.get<double>("coupling.surface_y_m", n);
  t.surface.z_m = in.get<double>("coupling.surface_z_m", n);
  t.surface.node_mass_kg = in.get<double>("coupling.surface_node_mass_kg", n);
  const auto e = in.get<std::uint64_t>("coupling.exchange", 2);
  t.exchange = e[0], t.substeps = static_cast<int>(e[1]), t.substep = 0;
  const auto d = in.get<double>("coupling.doubles", 14);
  t.band_m = d[1];
  t.load_totals.force_N = {d[2], d[3], d[4]};
  t.load_totals.contact_area_m2 = d[5];
  for (int c = 0; c < 3; ++c) t.impulse_Ns[c] = d[6 + c], t.window_impulse_Ns[c] = d[9 + c];
  t.loads.particle_reach_z_m = d[12], t.highest_band_m = d[13];
  return d[0];
}

}  // namespace tyre_fe
