#pragma once
// The terrain's SurfaceExchange over DDS: takes the tyre's surface mesh once
// and, each exchange, the kinematics of the surface near the terrain with the
// friction coefficient the coupler chose per facet; sends back the contact
// loads on the surface nodes and facets. It copies the exchange types
// (cosim/surface_exchange.hpp) to and from their wire topics and checks them.
#include <memory>
#include <vector>

#include "cosim_coupling/session.hpp"
#include "snow_sph/surface_exchange.hpp"

namespace snow_sph {

class DdsSurfaceExchange final : public SurfaceExchange {
 public:
  explicit DdsSurfaceExchange(cosim::coupling::Session& session);
  double connect(double proposed_dt_s, std::uint64_t start_exchange) override;
  const cosim::SurfaceState* surface(std::uint64_t exchange) override;
  const cosim::SurfaceTopology& topology() const override { return topology_; }
  void send_loads(const cosim::SurfaceLoads& loads) override;
  void finish(bool failed, const std::string& reason) override;
  void request_checkpoint_stop() override { session_.request_checkpoint_stop(); }
  std::uint64_t checkpoint_stop_exchange() const override { return session_.checkpoint_stop_exchange(); }

 private:
  cosim::coupling::Session& session_;
  std::unique_ptr<cosim::transport::Reader<cosim::transport::SurfaceMesh>> mesh_in_;
  std::unique_ptr<cosim::transport::Reader<cosim::transport::SurfaceKinematics>> kinematics_in_;
  std::unique_ptr<cosim::transport::Writer<cosim::transport::ContactLoads>> loads_out_;
  cosim::transport::SampleFilter filter_, mesh_filter_;
  cosim::transport::SurfaceMesh mesh_;
  cosim::transport::SurfaceKinematics kinematics_;
  cosim::transport::ContactLoads loads_;
  cosim::SurfaceTopology topology_;
  cosim::SurfaceState state_;
  std::uint64_t last_exchange_ = 0;
  bool have_mesh_ = false;
};

}  // namespace snow_sph
