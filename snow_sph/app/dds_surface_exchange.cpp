#include "dds_surface_exchange.hpp"

#include <string>

namespace snow_sph {

namespace tp = cosim::transport;

DdsSurfaceExchange::DdsSurfaceExchange(cosim::coupling::Session& session)
    : session_(session), filter_(session.run_id()), mesh_filter_(session.run_id()) {}

double DdsSurfaceExchange::connect(double proposed_dt_s) {
  auto& p = session_.participant();
  mesh_in_ = p.create_reader<tp::SurfaceMesh>();
  kinematics_in_ = p.create_reader<tp::SurfaceKinematics>(cosim::coupling::channel_qos<tp::SurfaceKinematics>(cosim::coupling::kTerrainChannel));
  loads_out_ = p.create_writer<tp::ContactLoads>(cosim::coupling::channel_qos<tp::ContactLoads>(cosim::coupling::kTerrainChannel));
  const tp::HandshakeResult joined =
      session_.join({tp::Role::coupler}, proposed_dt_s, {mesh_in_.get(), kinematics_in_.get(), loads_out_.get()});
  return session_.wait_for_start(joined);
}

const ContactSurface* DdsSurfaceExchange::surface(std::uint64_t exchange) {
  if (exchange == 0) {
    // The durable surface mesh is written with the first kinematics.
    if (!session_.wait_step(*mesh_in_, mesh_filter_, 0, mesh_, "SurfaceMesh", tp::Role::tyre)) return nullptr;
    compact_of_.assign(mesh_.node_ids.size(), -1);
  }
  if (!session_.wait_step(*kinematics_in_, filter_, exchange, kinematics_, "SurfaceKinematics", tp::Role::coupler))
    return nullptr;
  const tp::SurfaceKinematics& k = kinematics_;
  const std::string where = "SurfaceKinematics of step " + std::to_string(exchange) + ": ";
  const std::size_t n = k.nodes.size();
  if (k.x_m.size() != n || k.y_m.size() != n || k.z_m.size() != n || k.vx_mps.size() != n ||
      k.vy_mps.size() != n || k.vz_mps.size() != n)
    throw cosim::Error(where + "node sequences differ in length");
  if (k.friction_coefficient.size() != k.facets.size())
    throw cosim::Error(where + std::to_string(k.facets.size()) + " facets but " +
                       std::to_string(k.friction_coefficient.size()) + " friction coefficients");
  ContactSurface& s = surface_;
  s.x = k.x_m, s.y = k.y_m, s.z = k.z_m, s.vx = k.vx_mps, s.vy = k.vy_mps, s.vz = k.vz_mps;
  std::fill(compact_of_.begin(), compact_of_.end(), -1);
  for (std::size_t j = 0; j < n; ++j) {
    if (k.nodes[j] >= compact_of_.size())
      throw cosim::Error(where + "surface node " + std::to_string(k.nodes[j]) + " is not in the surface mesh");
    compact_of_[k.nodes[j]] = static_cast<std::int64_t>(j);
  }
  s.facet_nodes.clear();
  const std::size_t facet_total = mesh_.facet_tags.size();
  for (std::uint32_t f : k.facets) {
    if (f >= facet_total)
      throw cosim::Error(where + "facet " + std::to_string(f) + " is not in the surface mesh");
    for (int a = 0; a < 4; ++a) {
      const std::int64_t c = compact_of_[mesh_.facet_nodes[4 * f + a]];
      if (c < 0) throw cosim::Error(where + "facet " + std::to_string(f) + " has a node that was not sent");
      s.facet_nodes.push_back(static_cast<std::uint32_t>(c));
    }
  }
  s.friction_coefficient = k.friction_coefficient;
  s.node_mass_kg.clear();
  if (mesh_.node_mass_kg.size() == mesh_.node_ids.size())
    for (std::uint32_t node : k.nodes) s.node_mass_kg.push_back(mesh_.node_mass_kg[node]);
  s.facet_id.assign(k.facets.begin(), k.facets.end());
  last_exchange_ = exchange;
  last_time_s_ = k.header.sim_time_s;
  return &surface_;
}

void DdsSurfaceExchange::send_loads(std::uint64_t exchange, const SurfaceLoads& l) {
  const tp::SurfaceKinematics& k = kinematics_;
  tp::ContactLoads& out = loads_;
  out.header = {session_.run_id(), exchange, last_time_s_};
  out.nodes.clear(), out.fx_N.clear(), out.fy_N.clear(), out.fz_N.clear();
  for (std::size_t j = 0; j < k.nodes.size(); ++j) {
    if (l.node_fx[j] == 0.0 && l.node_fy[j] == 0.0 && l.node_fz[j] == 0.0) continue;
    out.nodes.push_back(k.nodes[j]);
    out.fx_N.push_back(l.node_fx[j]), out.fy_N.push_back(l.node_fy[j]), out.fz_N.push_back(l.node_fz[j]);
  }
  out.facets.clear(), out.normal_force_N.clear(), out.tangential_x_N.clear(), out.tangential_y_N.clear();
  out.tangential_z_N.clear(), out.contact_area_m2.clear(), out.pressure_Pa.clear();
  for (std::size_t f = 0; f < k.facets.size(); ++f) {
    if (l.particles_in_contact[f] == 0) continue;
    out.facets.push_back(k.facets[f]);
    out.normal_force_N.push_back(l.facet_normal_force_N[f]);
    out.tangential_x_N.push_back(l.facet_tangential_x_N[f]);
    out.tangential_y_N.push_back(l.facet_tangential_y_N[f]);
    out.tangential_z_N.push_back(l.facet_tangential_z_N[f]);
    out.contact_area_m2.push_back(l.facet_contact_area_m2[f]);
    out.pressure_Pa.push_back(l.facet_pressure_Pa[f]);
  }
  loads_out_->write(out);
}

void DdsSurfaceExchange::finish(bool failed, const std::string& reason) {
  if (failed) session_.send_failure(last_exchange_, "snow_sph: " + reason);
  session_.count_rejections(filter_);
}

}  // namespace snow_sph
