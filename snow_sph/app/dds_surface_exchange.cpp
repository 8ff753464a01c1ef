#include "dds_surface_exchange.hpp"

#include <string>

#include "cosim_coupling/exchange_topics.hpp"

namespace snow_sph {

namespace tp = cosim::transport;

DdsSurfaceExchange::DdsSurfaceExchange(cosim::coupling::Session& session)
    : session_(session), filter_(session.run_id()), mesh_filter_(session.run_id()) {}

double DdsSurfaceExchange::connect(double proposed_dt_s, std::uint64_t start_exchange) {
  auto& p = session_.participant();
  mesh_in_ = p.create_reader<tp::SurfaceMesh>();
  kinematics_in_ = p.create_reader<tp::SurfaceKinematics>(cosim::coupling::channel_qos<tp::SurfaceKinematics>(cosim::coupling::kTerrainChannel));
  loads_out_ = p.create_writer<tp::ContactLoads>(cosim::coupling::channel_qos<tp::ContactLoads>(cosim::coupling::kTerrainChannel));
  const tp::HandshakeResult joined =
      session_.join({tp::Role::coupler}, proposed_dt_s, {mesh_in_.get(), kinematics_in_.get(), loads_out_.get()}, start_exchange);
  return session_.wait_for_start(joined);
}

const cosim::SurfaceState* DdsSurfaceExchange::surface(std::uint64_t exchange) {
  if (!have_mesh_) {
    // The durable surface mesh (header step 0), written by the tyre when it
    // joins: before the first kinematics, of a run or of its restart.
    if (!session_.wait_step(*mesh_in_, mesh_filter_, 0, mesh_, "SurfaceMesh", tp::Role::tyre)) return nullptr;
    if (mesh_.x_m.size() != mesh_.node_ids.size())
      throw cosim::Error("SurfaceMesh: x_m has " + std::to_string(mesh_.x_m.size()) + " entries for " +
                         std::to_string(mesh_.node_ids.size()) + " nodes");
    cosim::coupling::from_topic(mesh_, topology_);
    cosim::check_surface_topology(topology_, "SurfaceMesh");
    have_mesh_ = true;
  }
  if (!session_.wait_step(*kinematics_in_, filter_, exchange, kinematics_, "SurfaceKinematics", tp::Role::coupler))
    return nullptr;
  cosim::coupling::from_topic(kinematics_, state_);
  // The coupler decides every facet's friction: the terrain must have one per facet.
  cosim::check_surface_state(state_, topology_, "SurfaceKinematics of step " + std::to_string(exchange),
                             /*friction_required=*/true);
  last_exchange_ = exchange;
  return &state_;
}

void DdsSurfaceExchange::send_loads(const cosim::SurfaceLoads& l) {
  cosim::coupling::to_topic(l, session_.run_id(), loads_);
  loads_out_->write(loads_);
}

void DdsSurfaceExchange::finish(bool failed, const std::string& reason) {
  if (failed) session_.send_failure(last_exchange_, "snow_sph: " + reason);
  session_.count_rejections(filter_);
}

}  // namespace snow_sph
