#pragma once
// The tyre's TerrainPort over DDS: publishes the contact surface once, then
// per exchange the wheel state and the surface near the terrain, and takes the
// contact loads the coupler forwards from the terrain. It copies the exchange
// types (cosim/surface_exchange.hpp) to and from their wire topics.
#include <memory>

#include "cosim_coupling/session.hpp"
#include "tyre_fe/solver3d.hpp"
#include "tyre_fe/terrain_port.hpp"

namespace tyre_fe {

class DdsTerrainPort final : public TerrainPort {
 public:
  explicit DdsTerrainPort(cosim::coupling::Session& session);
  double connect(const ContactSurfaceDef& surface, double proposed_dt_s, std::uint64_t start_exchange,
                 double start_time_s) override;
  void send(const cosim::SurfaceState& surface, const RimState& rim) override;
  void receive(std::uint64_t exchange, cosim::SurfaceLoads& loads) override;
  void finish(bool failed, const std::string& reason) override;
  void request_checkpoint_stop() override { session_.request_checkpoint_stop(); }
  std::uint64_t checkpoint_stop_exchange() const override { return session_.checkpoint_stop_exchange(); }

 private:
  cosim::coupling::Session& session_;
  const ContactSurfaceDef* surface_ = nullptr;
  std::unique_ptr<cosim::transport::Writer<cosim::transport::SurfaceMesh>> mesh_out_;
  std::unique_ptr<cosim::transport::Writer<cosim::transport::SurfaceKinematics>> kinematics_out_;
  std::unique_ptr<cosim::transport::Writer<cosim::transport::WheelState>> wheel_out_;
  std::unique_ptr<cosim::transport::Reader<cosim::transport::ContactLoads>> loads_in_;
  cosim::transport::SampleFilter filter_;
  cosim::transport::SurfaceMesh mesh_;
  cosim::transport::SurfaceKinematics kinematics_;
  cosim::transport::ContactLoads loads_;
  std::uint64_t last_exchange_ = 0;
};

}  // namespace tyre_fe
