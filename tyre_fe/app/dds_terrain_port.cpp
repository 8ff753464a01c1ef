#include "dds_terrain_port.hpp"

#include "cosim_coupling/exchange_topics.hpp"

namespace tyre_fe {

namespace tp = cosim::transport;

DdsTerrainPort::DdsTerrainPort(cosim::coupling::Session& session)
    : session_(session), filter_(session.run_id()) {}

double DdsTerrainPort::connect(const ContactSurfaceDef& surface, double proposed_dt_s, std::uint64_t start_exchange,
                               double start_time_s) {
  surface_ = &surface;
  auto& p = session_.participant();
  mesh_out_ = p.create_writer<tp::SurfaceMesh>();
  kinematics_out_ = p.create_writer<tp::SurfaceKinematics>(cosim::coupling::channel_qos<tp::SurfaceKinematics>(cosim::coupling::kTyreChannel));
  wheel_out_ = p.create_writer<tp::WheelState>();
  loads_in_ = p.create_reader<tp::ContactLoads>(cosim::coupling::channel_qos<tp::ContactLoads>(cosim::coupling::kTyreChannel));
  mesh_.node_ids.assign(surface.node_ids.begin(), surface.node_ids.end());
  cosim::coupling::to_topic(surface, mesh_);
  const tp::HandshakeResult joined =
      session_.join({tp::Role::coupler}, proposed_dt_s,
                    {mesh_out_.get(), kinematics_out_.get(), wheel_out_.get(), loads_in_.get()}, start_exchange);
  // The surface, durable (step 0 of the run, at the time the tyre joined it or
  // its restart's): the coupler, the terrain and any late monitor get it.
  mesh_.header = {session_.run_id(), 0, start_time_s};
  mesh_out_->write(mesh_);
  return session_.wait_for_start(joined);
}

void DdsTerrainPort::send(const cosim::SurfaceState& surface, const RimState& rim) {
  const tp::SampleHeader header{session_.run_id(), surface.exchange, surface.time_s};
  tp::WheelState w;
  w.header = header;
  w.rim_x_m = rim.x, w.rim_z_m = rim.z, w.rotation_angle_rad = rim.angle;
  w.forward_speed_mps = rim.vx, w.spin_rate_radps = rim.omega;
  w.applied_torque_Nm = rim.applied_torque_Nm, w.reaction_moment_y_Nm = rim.rm2_Nm;
  w.wheel_load_N = rim.wheel_load_N;
  w.rim_longitudinal_force_N = rim.tyre_force_x_N;
  wheel_out_->write(w);
  cosim::coupling::to_topic(surface, session_.run_id(), kinematics_);
  kinematics_out_->write(kinematics_);
  last_exchange_ = surface.exchange;
}

void DdsTerrainPort::receive(std::uint64_t exchange, cosim::SurfaceLoads& loads) {
  if (!session_.wait_step(*loads_in_, filter_, exchange, loads_, "ContactLoads", tp::Role::coupler))
    throw cosim::Error("the run was stopped by another process at step " + std::to_string(exchange));
  cosim::coupling::from_topic(loads_, loads);
  cosim::check_surface_loads(loads, *surface_, "ContactLoads of step " + std::to_string(exchange));
}

void DdsTerrainPort::finish(bool failed, const std::string& reason) {
  if (failed)
    session_.send_failure(last_exchange_, "tyre_fe: " + reason);
  else
    session_.send_stop(last_exchange_ + 1, "the tyre's stages are complete");
  session_.count_rejections(filter_);
}

}  // namespace tyre_fe
