#pragma once
// The tyre's side of a coupling with a terrain solver, without any transport:
// the contact surface the tyre offers (nodes, quad facets, tags), the loads the
// terrain returns, and the port through which the step loop exchanges them.
// tyre_fe's library never knows what is behind the port (DDS in the
// coupled executable); what crosses it are the exchange types both solvers
// share (cosim/surface_exchange.hpp).
//
// Timing (explicit central difference, Belytschko et al. 2000 box 6.1): at the
// start of coupling window n the tyre sends its surface at t_n (positions x^n,
// velocities v^{n-1/2}), then computes its element forces while the terrain
// works, then receives the contact loads of t_n and adds them to the nodal
// forces of every sub-step of the window (docs/coupling.md).
#include <cstdint>
#include <string>
#include <vector>

#include "cosim/participant.hpp"
#include "cosim/surface_exchange.hpp"
#include "tyre_fe/model3d.hpp"

namespace tyre_fe {

struct State3d;
struct RimState;

// The outer surface that can touch a terrain: every tagged facet except the
// inner liner and the rim faces, as the topology every participant sees
// (cosim/surface_exchange.hpp) plus where it sits in the tyre's mesh. Surface
// node k is model node node_ids[k]; surface facet f is mesh.facets[mesh_facets[f]].
struct ContactSurfaceDef : cosim::SurfaceTopology {
  std::vector<int> node_ids;
  std::vector<int> mesh_facets;
};
// Positions from the mesh's reference nodes, no node masses.
ContactSurfaceDef make_contact_surface(const Mesh3D& mesh);
// With the lumped masses of the model's nodes and the positions of state s.
ContactSurfaceDef make_contact_surface(const Model3d& model, const State3d& s);

// The part of the surface near the terrain (its undisturbed surface is z = 0)
// at state s: the facets with a node below band_m, and their nodes, with the
// exchange and time of s's terrain coupling.
void surface_near_terrain(const ContactSurfaceDef& surface, const State3d& s, double band_m,
                          cosim::SurfaceState& out);

class TerrainPort {
 public:
  virtual ~TerrainPort() = default;
  // Once, before the first coupled step: offers the surface and this solver's
  // stable step; returns the common step every participant will use.
  // `start_exchange`, `start_time_s`: where the run starts (a restart: its
  // checkpoint's exchange and time; every peer must start at that exchange).
  virtual double connect(const ContactSurfaceDef& surface, double proposed_dt_s, std::uint64_t start_exchange,
                         double start_time_s) = 0;
  // The surface near the terrain at exchange surface.exchange (0, 1, ...), and the rim.
  virtual void send(const cosim::SurfaceState& surface, const RimState& rim) = 0;
  // The loads of the same exchange; throws cosim::Error if the terrain is gone.
  virtual void receive(std::uint64_t exchange, cosim::SurfaceLoads& loads) = 0;
  // End of the run: normal stop (failed = false) or failure with a reason.
  virtual void finish(bool failed, const std::string& reason) = 0;
  // A stop signal: asks the run for a stop at a common checkpoint; the exchange
  // named for it once known (0: none yet; docs/reliability.md).
  virtual void request_checkpoint_stop() = 0;
  virtual std::uint64_t checkpoint_stop_exchange() const = 0;
};

// A run that failed tells its peers through its port, if it has one; never throws
// (if the message cannot go, the peers learn of the failure by their time-out).
void report_failure(TerrainPort* port, const std::string& reason) noexcept;

// A tyre_fe participant on a terrain port, or on none (a rigid road): at the run's
// end it releases its peers, on a failure it tells them why. The tyre and the tread
// block share this; what they step differs.
class PortParticipant : public cosim::Participant {
 public:
  void finish_peers() override {
    if (port_) port_->finish(false, "");
  }
  void abort(const std::string& reason) noexcept override {
    failed_ = true;
    report_failure(port_, reason);
  }

 protected:
  explicit PortParticipant(TerrainPort* port) : port_(port) {}
  TerrainPort* port_;
  bool failed_ = false;
};

}  // namespace tyre_fe
