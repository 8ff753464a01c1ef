#pragma once
// The terrain's side of a coupling with a solver that owns a contact surface
// (the tyre), without any transport: the run asks the port for the surface
// of each exchange and hands back the loads the solver computed, both in the
// types the tyre's side uses too (cosim/surface_exchange.hpp).
// What is behind the port (DDS in the coupled executable, a test double in
// tests) is not the solver's business. What every link to the peers offers
// (the run's end, a stop at a checkpoint) is cosim::coupling::PeerLink's.
//
// Timing: exchange n belongs to time t_n. initialise() makes exchange 0 with
// the particles at t_0; step k (k = 1, 2, ...) makes exchange k with the
// particles at t_k, after the particle forces and before the kick that uses
// them, so the contact forces of both sides belong to the same instant.
#include <cstdint>

#include "cosim_coupling/coupled_participant.hpp"
#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

class SurfaceExchange : public cosim::coupling::PeerLink {
 public:
  // Once, before initialise(): this solver's stable step in, the common step
  // out. `start_exchange`: 0, or a restart's first exchange (every peer must agree).
  virtual double connect(double proposed_dt_s, std::uint64_t start_exchange) = 0;
  // The surface's state at exchange n; null when the owner of the surface ended the run.
  virtual const cosim::SurfaceState* surface(std::uint64_t exchange) = 0;
  // The surface's topology, once the first surface() has returned.
  virtual const cosim::SurfaceTopology& topology() const = 0;
  // The loads computed at the exchange they name.
  virtual void send_loads(const cosim::SurfaceLoads& loads) = 0;
};

}  // namespace snow_sph
