#include "cosim_coupling/exchange_topics.hpp"

namespace cosim::coupling {

void to_topic(const SurfaceState& s, std::uint64_t run_id, transport::SurfaceKinematics& k) {
  k.header = {run_id, s.exchange, s.time_s};
  k.nodes = s.nodes;
  k.x_m = s.x_m, k.y_m = s.y_m, k.z_m = s.z_m;
  k.vx_mps = s.vx_mps, k.vy_mps = s.vy_mps, k.vz_mps = s.vz_mps;
  k.facets = s.facets;
  k.friction_coefficient = s.friction_coefficient;
}

void from_topic(const transport::SurfaceKinematics& k, SurfaceState& s) {
  s.exchange = k.header.step, s.time_s = k.header.sim_time_s;
  s.nodes = k.nodes;
  s.x_m = k.x_m, s.y_m = k.y_m, s.z_m = k.z_m;
  s.vx_mps = k.vx_mps, s.vy_mps = k.vy_mps, s.vz_mps = k.vz_mps;
  s.facets = k.facets;
  s.friction_coefficient = k.friction_coefficient;
}

void to_topic(const SurfaceLoads& l, std::uint64_t run_id, transport::ContactLoads& out) {
  out.header = {run_id, l.exchange, l.time_s};
  out.nodes = l.nodes;
  out.fx_N = l.fx_N, out.fy_N = l.fy_N, out.fz_N = l.fz_N;
  out.facets = l.facets;
  out.normal_force_N = l.normal_force_N;
  out.tangential_x_N = l.tangential_x_N, out.tangential_y_N = l.tangential_y_N, out.tangential_z_N = l.tangential_z_N;
  out.contact_area_m2 = l.contact_area_m2;
  out.pressure_Pa = l.pressure_Pa;
}

void from_topic(const transport::ContactLoads& l, SurfaceLoads& out) {
  out.exchange = l.header.step, out.time_s = l.header.sim_time_s;
  out.nodes = l.nodes;
  out.fx_N = l.fx_N, out.fy_N = l.fy_N, out.fz_N = l.fz_N;
  out.facets = l.facets;
  out.normal_force_N = l.normal_force_N;
  out.tangential_x_N = l.tangential_x_N, out.tangential_y_N = l.tangential_y_N, out.tangential_z_N = l.tangential_z_N;
  out.contact_area_m2 = l.contact_area_m2;
  out.pressure_Pa = l.pressure_Pa;
}

void from_topic(const transport::SurfaceMesh& m, SurfaceTopology& out) {
  out.x_m = m.x_m, out.y_m = m.y_m, out.z_m = m.z_m;
  out.facet_nodes = m.facet_nodes;
  out.facet_tags = m.facet_tags;
  out.node_mass_kg = m.node_mass_kg;
}

}  // namespace cosim::coupling
