#pragma once
// The terrain's SurfaceExchange over DDS: takes the tyre's surface mesh once
// and, each step, the kinematics of the surface near the terrain with the
// friction coefficient the coupler chose per facet; sends back the contact
// loads on the surface nodes and facets.
#include <memory>
#include <vector>

#include "cosim_coupling/session.hpp"
#include "snow_sph/surface_exchange.hpp"

namespace snow_sph {

class DdsSurfaceExchange final : public SurfaceExchange {
 public:
  explicit DdsSurfaceExchange(cosim::coupling::Session& session);
  double connect(double proposed_dt_s) override;
  const ContactSurface* surface(std::uint64_t exchange) override;
  void send_loads(std::uint64_t exchange, const SurfaceLoads& loads) override;
  void finish(bool failed, const std::string& reason) override;

 private:
  cosim::coupling::Session& session_;
  std::unique_ptr<cosim::transport::Reader<cosim::transport::SurfaceMesh>> mesh_in_;
  std::unique_ptr<cosim::transport::Reader<cosim::transport::SurfaceKinematics>> kinematics_in_;
  std::unique_ptr<cosim::transport::Writer<cosim::transport::ContactLoads>> loads_out_;
  cosim::transport::SampleFilter filter_, mesh_filter_;
  cosim::transport::SurfaceMesh mesh_;
  cosim::transport::SurfaceKinematics kinematics_;
  cosim::transport::ContactLoads loads_;
  ContactSurface surface_;
  std::vector<std::int64_t> compact_of_;  // surface node -> index in surface_ (-1: not sent)
  std::uint64_t last_exchange_ = 0;
  double last_time_s_ = 0.0;
};

}  // namespace snow_sph
