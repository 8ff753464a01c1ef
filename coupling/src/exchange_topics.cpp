#include "cosim_coupling/exchange_topics.hpp"

namespace cosim::coupling {
namespace {

// The exchange types and their topics name their fields alike (the topics add
// a header; the mesh topic adds the tyre's node ids), so one copy of the
// fields serves both directions.
template <class From, class To>
void copy_kinematics(const From& a, To& b) {
  b.nodes = a.nodes;
  b.x_m = a.x_m, b.y_m = a.y_m, b.z_m = a.z_m;
  b.vx_mps = a.vx_mps, b.vy_mps = a.vy_mps, b.vz_mps = a.vz_mps;
  b.facets = a.facets;
  b.friction_coefficient = a.friction_coefficient;
}

template <class From, class To>
void copy_loads(const From& a, To& b) {
  b.nodes = a.nodes;
  b.fx_N = a.fx_N, b.fy_N = a.fy_N, b.fz_N = a.fz_N;
  b.facets = a.facets;
  b.normal_force_N = a.normal_force_N;
  b.pressure_x_N = a.pressure_x_N, b.pressure_y_N = a.pressure_y_N, b.pressure_z_N = a.pressure_z_N;
  b.tangential_x_N = a.tangential_x_N, b.tangential_y_N = a.tangential_y_N, b.tangential_z_N = a.tangential_z_N;
  b.contact_area_m2 = a.contact_area_m2;
  b.pressure_Pa = a.pressure_Pa;
  b.particle_reach_z_m = a.particle_reach_z_m;
}

template <class From, class To>
void copy_topology(const From& a, To& b) {
  b.x_m = a.x_m, b.y_m = a.y_m, b.z_m = a.z_m;
  b.facet_nodes = a.facet_nodes;
  b.facet_tags = a.facet_tags;
  b.node_mass_kg = a.node_mass_kg;
}

}  // namespace

void to_topic(const SurfaceState& s, std::uint64_t run_id, transport::SurfaceKinematics& k) {
  k.header = {run_id, s.exchange, s.time_s};
  copy_kinematics(s, k);
}

void from_topic(const transport::SurfaceKinematics& k, SurfaceState& s) {
  s.exchange = k.header.step, s.time_s = k.header.sim_time_s;
  copy_kinematics(k, s);
}

void to_topic(const SurfaceLoads& l, std::uint64_t run_id, transport::ContactLoads& out) {
  out.header = {run_id, l.exchange, l.time_s};
  copy_loads(l, out);
}

void from_topic(const transport::ContactLoads& l, SurfaceLoads& out) {
  out.exchange = l.header.step, out.time_s = l.header.sim_time_s;
  copy_loads(l, out);
}

void to_topic(const SurfaceTopology& t, transport::SurfaceMesh& out) { copy_topology(t, out); }

void from_topic(const transport::SurfaceMesh& m, SurfaceTopology& out) { copy_topology(m, out); }

}  // namespace cosim::coupling
