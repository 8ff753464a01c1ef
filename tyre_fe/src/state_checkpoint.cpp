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
  return std::vector<std::pair<const char*, decltype(&s.time_s)>>{
      {"rim.x", &r.x},
      {"rim.z", &r.z},
      {"rim.angle", &r.angle},
      {"rim.vx", &r.vx},
      {"rim.vz", &r.vz},
      {"rim.omega", &r.omega},
      {"rim.mass_kg", &r.mass_kg},
      {"rim.inertia_kg_m2", &r.inertia_kg_m2},
      {"rim.tyre_force_x_N", &r.tyre_force_x_N},
      {"rim.tyre_force_z_N", &r.tyre_force_z_N},
      {"rim.tyre_moment_y_Nm", &r.tyre_moment_y_Nm},
      {"rim.rm2_Nm", &r.rm2_Nm},
      {"rim.applied_torque_Nm", &r.applied_torque_Nm},
      {"rim.wheel_load_N", &r.wheel_load_N},
      {"road.height_m", &road.height_m},
      {"road.friction_coefficient", &road.friction_coefficient},
      {"road.penalty_scale", &road.penalty_scale},
      {"road.force_x_N", &road.force_x_N},
      {"road.force_y_N", &road.force_y_N},
      {"road.force_z_N", &road.force_z_N},
      {"road.contact_area_m2", &road.contact_area_m2},
      {"road.friction_dissipation_J", &road.friction_dissipation_J},
      {"energy.kinetic_J", &e.kinetic_J},
      {"energy.internal_J", &e.internal_J},
      {"energy.hourglass_J", &e.hourglass_J},
      {"energy.external_work_J", &e.external_work_J},
      {"energy.damping_work_J", &e.damping_work_J},
      {"energy.contact_work_J", &e.contact_work_J},
      {"energy.initial_J", &e.initial_J},
      {"energy.pressure_work_J", &e.pressure_work_J},
      {"energy.bulk_viscous_work_J", &e.bulk_viscous_work_J},
      {"energy.initial_internal_J", &e.initial_internal_J},
      {"energy.initial_hourglass_J", &e.initial_hourglass_J},
      {"pressure_Pa", &s.pressure_Pa},
      {"damping_per_s", &s.damping_per_s},
      {"time_s", &s.time_s},
      {"dt_s", &s.dt_s}};
}

}  // namespace

void save_state(const State3d& s, cosim::CheckpointWriter& out) {
  for (auto& [name, v] : arrays(s)) out.put(std::string("tyre.") + name, *v);
  for (auto& [name, v] : scalars(s)) out.put_value<double>(std::string("tyre.") + name, *v);
  out.put("tyre.road.in_contact", std::vector<std::uint8_t>(s.road.in_contact.begin(), s.road.in_contact.end()));
  out.put_value<std::uint64_t>("tyre.step", s.step);
  out.put_value<std::uint8_t>("tyre.road.present", s.road.present ? 1 : 0);
}

void restore_state(const cosim::CheckpointReader& in, State3d& s) {
  for (auto& [name, v] : arrays(s)) {
    const std::string key = std::string("tyre.") + name;
    // The road's arrays are empty until the road is placed (the loading stage).
    *v = std::string(name).rfind("road.", 0) == 0 ? in.get<double>(key) : in.get<double>(key, v->size());
  }
  for (auto& [name, v] : scalars(s)) *v = in.get_value<double>(std::string("tyre.") + name);
  const auto contact = in.get<std::uint8_t>("tyre.road.in_contact", s.road.anchor_x.size());
  s.road.in_contact.assign(contact.begin(), contact.end());
  s.step = in.get_value<std::uint64_t>("tyre.step");
  s.road.present = in.get_value<std::uint8_t>("tyre.road.present") != 0;
}

void save_terrain_coupling(const TerrainCoupling& t, double window_s, cosim::CheckpointWriter& out) {
  if (t.substep != 0) throw cosim::Error("a coupled tyre's checkpoint is taken between windows only");
  out.put("coupling.surface_x_m", t.surface.x_m);
  out.put("coupling.surface_y_m", t.surface.y_m);
  out.put("coupling.surface_z_m", t.surface.z_m);
  out.put("coupling.surface_node_mass_kg", t.surface.node_mass_kg);
  out.put_value<std::uint64_t>("coupling.exchange", t.exchange);
  out.put_value<std::uint64_t>("coupling.substeps", static_cast<std::uint64_t>(t.substeps));
  out.put_value<double>("coupling.window_s", window_s);
  out.put_value<double>("coupling.band_m", t.band_m);
  out.put("coupling.load_force_N", std::vector<double>(t.load_totals.force_N.begin(), t.load_totals.force_N.end()));
  out.put_value<double>("coupling.load_contact_area_m2", t.load_totals.contact_area_m2);
  out.put("coupling.impulse_Ns", std::vector<double>(t.impulse_Ns, t.impulse_Ns + 3));
  out.put("coupling.window_impulse_Ns", std::vector<double>(t.window_impulse_Ns, t.window_impulse_Ns + 3));
  out.put_value<double>("coupling.particle_reach_z_m", t.loads.particle_reach_z_m);
  out.put_value<double>("coupling.highest_band_m", t.highest_band_m);
}

double restore_terrain_coupling(const cosim::CheckpointReader& in, TerrainCoupling& t) {
  const std::size_t n = t.surface.node_ids.size();
  t.surface.x_m = in.get<double>("coupling.surface_x_m", n);
  t.surface.y_m = in.get<double>("coupling.surface_y_m", n);
  t.surface.z_m = in.get<double>("coupling.surface_z_m", n);
  t.surface.node_mass_kg = in.get<double>("coupling.surface_node_mass_kg", n);
  t.exchange = in.get_value<std::uint64_t>("coupling.exchange");
  t.substeps = static_cast<int>(in.get_value<std::uint64_t>("coupling.substeps")), t.substep = 0;
  t.band_m = in.get_value<double>("coupling.band_m");
  const auto force = in.get<double>("coupling.load_force_N", 3);
  t.load_totals.force_N = {force[0], force[1], force[2]};
  t.load_totals.contact_area_m2 = in.get_value<double>("coupling.load_contact_area_m2");
  const auto impulse = in.get<double>("coupling.impulse_Ns", 3), window = in.get<double>("coupling.window_impulse_Ns", 3);
  for (int c = 0; c < 3; ++c) t.impulse_Ns[c] = impulse[c], t.window_impulse_Ns[c] = window[c];
  t.loads.particle_reach_z_m = in.get_value<double>("coupling.particle_reach_z_m");
  t.highest_band_m = in.get_value<double>("coupling.highest_band_m");
  return in.get_value<double>("coupling.window_s");
}

}  // namespace tyre_fe
