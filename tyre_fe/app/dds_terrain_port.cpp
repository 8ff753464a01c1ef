#include "dds_terrain_port.hpp"

#include <algorithm>

namespace tyre_fe {

namespace tp = cosim::transport;

DdsTerrainPort::DdsTerrainPort(cosim::coupling::Session& session, double contact_band_m)
    : session_(session), band_m_(contact_band_m), filter_(session.run_id()) {}

double DdsTerrainPort::connect(const ContactSurfaceDef& surface, double proposed_dt_s) {
  surface_ = &surface;
  auto& p = session_.participant();
  mesh_out_ = p.create_writer<tp::SurfaceMesh>();
  kinematics_out_ = p.create_writer<tp::SurfaceKinematics>(cosim::coupling::channel_qos<tp::SurfaceKinematics>(cosim::coupling::kTyreChannel));
  wheel_out_ = p.create_writer<tp::WheelState>();
  loads_in_ = p.create_reader<tp::ContactLoads>(cosim::coupling::channel_qos<tp::ContactLoads>(cosim::coupling::kTyreChannel));
  // The surface, durable: the coupler, the terrain and any late monitor get it.
  tp::SurfaceMesh mesh;
  mesh.header = {session_.run_id(), 0, 0.0};
  for (int n : surface.node_ids) mesh.node_ids.push_back(static_cast<std::uint32_t>(n));
  mesh.facet_nodes = surface.facet_nodes;
  mesh.facet_tags.assign(surface.facet_tags.begin(), surface.facet_tags.end());
  mesh.node_mass_kg = surface.node_mass_kg;
  mesh_ = std::move(mesh);  // positions are added by the first send()
  const tp::HandshakeResult joined =
      session_.join({tp::Role::coupler}, proposed_dt_s,
                    {mesh_out_.get(), kinematics_out_.get(), wheel_out_.get(), loads_in_.get()});
  return session_.wait_for_start(joined);
}

void DdsTerrainPort::send(std::uint64_t exchange, const State3d& s, const Model3d& model) {
  (void)model;
  const ContactSurfaceDef& surface = *surface_;
  const tp::SampleHeader header{session_.run_id(), exchange, s.time_s};
  if (exchange == 0) {
    // Reference positions of the surface: the state the coupled run starts from.
    for (int n : surface.node_ids) mesh_.x_m.push_back(s.x[n]), mesh_.y_m.push_back(s.y[n]), mesh_.z_m.push_back(s.z[n]);
    mesh_.header = header;
    mesh_out_->write(mesh_);
  }
  tp::WheelState w;
  w.header = header;
  w.rim_x_m = s.rim.x, w.rim_z_m = s.rim.z, w.rotation_angle_rad = s.rim.angle;
  w.forward_speed_mps = s.rim.vx, w.spin_rate_radps = s.rim.omega;
  w.applied_torque_Nm = s.rim.applied_torque_Nm, w.reaction_moment_y_Nm = s.rim.rm2_Nm;
  w.wheel_load_N = s.rim.wheel_load_N;
  wheel_out_->write(w);
  // The surface near the terrain: facets with a node below the band, and their nodes.
  tp::SurfaceKinematics& k = kinematics_;
  k.header = header;
  k.nodes.clear(), k.facets.clear(), k.friction_coefficient.clear();
  k.x_m.clear(), k.y_m.clear(), k.z_m.clear(), k.vx_mps.clear(), k.vy_mps.clear(), k.vz_mps.clear();
  node_sent_.assign(surface.node_ids.size(), 0);
  for (std::size_t f = 0; f < surface.facet_count(); ++f) {
    const std::uint32_t* fn = &surface.facet_nodes[4 * f];
    bool near = false;
    for (int a = 0; a < 4; ++a) near = near || s.z[surface.node_ids[fn[a]]] < band_m_;
    if (!near) continue;
    k.facets.push_back(static_cast<std::uint32_t>(f));
    for (int a = 0; a < 4; ++a) node_sent_[fn[a]] = 1;
  }
  for (std::size_t j = 0; j < surface.node_ids.size(); ++j) {
    if (!node_sent_[j]) continue;
    const int i = surface.node_ids[j];
    k.nodes.push_back(static_cast<std::uint32_t>(j));
    k.x_m.push_back(s.x[i]), k.y_m.push_back(s.y[i]), k.z_m.push_back(s.z[i]);
    k.vx_mps.push_back(s.vx[i]), k.vy_mps.push_back(s.vy[i]), k.vz_mps.push_back(s.vz[i]);
  }
  kinematics_out_->write(k);
  last_exchange_ = exchange;
}

void DdsTerrainPort::receive(std::uint64_t exchange, TerrainLoads& loads) {
  if (!session_.wait_step(*loads_in_, filter_, exchange, loads_, "ContactLoads", tp::Role::coupler))
    throw cosim::Error("the run was stopped by another process at step " + std::to_string(exchange));
  const tp::ContactLoads& l = loads_;
  const std::size_t n = l.nodes.size();
  if (l.fx_N.size() != n || l.fy_N.size() != n || l.fz_N.size() != n)
    throw cosim::Error("ContactLoads of step " + std::to_string(exchange) + ": node and force sequences differ in length");
  loads.surface_nodes = l.nodes;
  loads.fx_N = l.fx_N, loads.fy_N = l.fy_N, loads.fz_N = l.fz_N;
  loads.total_x_N = loads.total_y_N = loads.total_z_N = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (l.nodes[k] >= surface_->node_ids.size())
      throw cosim::Error("ContactLoads of step " + std::to_string(exchange) + ": surface node " +
                         std::to_string(l.nodes[k]) + " does not exist (" + std::to_string(surface_->node_ids.size()) +
                         " surface nodes)");
    loads.total_x_N += l.fx_N[k], loads.total_y_N += l.fy_N[k], loads.total_z_N += l.fz_N[k];
  }
  loads.contact_area_m2 = 0.0;
  for (double a : l.contact_area_m2) loads.contact_area_m2 += a;
  if (l.pressure_Pa.size() != l.facets.size())
    throw cosim::Error("ContactLoads of step " + std::to_string(exchange) + ": facet and pressure sequences differ in length");
  for (std::uint32_t f : l.facets)
    if (f >= surface_->facet_count())
      throw cosim::Error("ContactLoads of step " + std::to_string(exchange) + ": surface facet " + std::to_string(f) +
                         " does not exist (" + std::to_string(surface_->facet_count()) + " surface facets)");
  loads.facets = l.facets;
  loads.facet_pressure_Pa = l.pressure_Pa;
}

void DdsTerrainPort::finish(bool failed, const std::string& reason) {
  if (failed)
    session_.send_failure(last_exchange_, "tyre_fe: " + reason);
  else
    session_.send_stop(last_exchange_ + 1, "the tyre's stages are complete");
  session_.count_rejections(filter_);
}

}  // namespace tyre_fe
