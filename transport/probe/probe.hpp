#pragma once
// A lock-step exchange shaped like the coupled scene, for checking the
// transport across processes and vendors and for timing it
// (cosim_transport_probe, bench/exchange_bench):
//   ping (tyre role):    publish the SurfaceMesh once, handshake, then per step
//                        write SurfaceKinematics of N nodes and N facets and
//                        wait for that step's ContactLoads; finally send STOP;
//   pong (terrain role): handshake, read the durable SurfaceMesh, then per step
//                        wait for the kinematics and answer with ContactLoads of
//                        N/4 nodes and N/4 facets; stop on STOP.
// Every value is a known function of (field, step, index), so each side
// checks the content it receives exactly.
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "cosim_transport/topics.hpp"
#include "cosim_transport/transport.hpp"

namespace cosim::transport::probe {

struct ProbeOptions {
  Vendor vendor = Vendor::cyclone;
  TransportOptions transport;
  std::uint64_t run_id = 0;
  int nodes = 1000;        // surface nodes near the terrain (N)
  int steps = 200;
  int warmup_steps = 0;    // ping: exchanged first, not timed
  bool check_content = true;
  std::chrono::milliseconds timeout{20000};  // handshake and each wait
};

struct ProbeResult {
  int steps = 0;                         // exchanged and checked (timed ones for ping)
  std::vector<double> step_us;           // ping: write-to-loads time of each timed step
  std::uint64_t rejected = 0;            // samples of another run id or step
  std::size_t kinematics_bytes = 0;      // payload of one sample (sequences only)
  std::size_t loads_bytes = 0;
};

SurfaceMesh make_mesh(std::uint64_t run_id, int nodes);
SurfaceKinematics make_kinematics(std::uint64_t run_id, std::uint64_t step, int nodes);
ContactLoads make_loads(std::uint64_t run_id, std::uint64_t step, int nodes);
// Throw cosim::Error naming the first field that differs from the expected content.
void check_mesh(const SurfaceMesh& got, std::uint64_t run_id, int nodes);
void check_kinematics(const SurfaceKinematics& got, std::uint64_t run_id, std::uint64_t step, int nodes);
void check_loads(const ContactLoads& got, std::uint64_t run_id, std::uint64_t step, int nodes);

// Each throws cosim::Error on a timeout, a handshake failure or wrong content.
ProbeResult run_ping(const ProbeOptions& options);
ProbeResult run_pong(const ProbeOptions& options);

// Median and 99th percentile of `values` (nearest rank); 0 for none.
double percentile(std::vector<double> values, double fraction);

}  // namespace cosim::transport::probe
