#pragma once
// The tyre's TerrainPort over DDS: publishes the contact surface once, then
// per step the wheel state and the kinematics of the surface near the terrain,
// and takes the contact loads the coupler forwards from the terrain.
#include <memory>

#include "cosim_coupling/session.hpp"
#include "tyre_fe/solver3d.hpp"
#include "tyre_fe/terrain_port.hpp"

namespace tyre_fe {

class DdsTerrainPort final : public TerrainPort {
 public:
  // Surface facets with a node below `contact_band_m` (terrain surface z = 0) are sent each step.
  DdsTerrainPort(cosim::coupling::Session& session, double contact_band_m);
  double connect(const ContactSurfaceDef& surface, double proposed_dt_s) override;
  void send(std::uint64_t exchange, const State3d& s, const Model3d& model) override;
  void receive(std::uint64_t exchange, TerrainLoads& loads) override;
  void finish(bool failed, const std::string& reason) override;

 private:
  cosim::coupling::Session& session_;
  double band_m_;
  const ContactSurfaceDef* surface_ = nullptr;
  std::unique_ptr<cosim::transport::Writer<cosim::transport::SurfaceMesh>> mesh_out_;
  std::unique_ptr<cosim::transport::Writer<cosim::transport::SurfaceKinematics>> kinematics_out_;
  std::unique_ptr<cosim::transport::Writer<cosim::transport::WheelState>> wheel_out_;
  std::unique_ptr<cosim::transport::Reader<cosim::transport::ContactLoads>> loads_in_;
  cosim::transport::SampleFilter filter_;
  cosim::transport::SurfaceMesh mesh_;
  cosim::transport::SurfaceKinematics kinematics_;
  cosim::transport::ContactLoads loads_;
  std::vector<char> node_sent_;
  std::uint64_t last_exchange_ = 0;
};

}  // namespace tyre_fe
