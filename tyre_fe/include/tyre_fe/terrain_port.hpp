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

#include "cosim/surface_exchange.hpp"
#include "cosim_coupling/coupled_participant.hpp"
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

// What the tyre exchanges with its peers; the end of the run, a failure and a
// stop at a common checkpoint go through the link every participant shares
// (cosim::coupling::PeerLink).
class TerrainPort : public cosim::coupling::PeerLink {
 public:
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
};

}  // namespace tyre_fe
