#pragma once
// The command-line options every program of a coupled run shares (tyre_fe,
// snow_sph, coupler): vendor, run id, domain and discovery. `cosim run` passes
// them to the processes it starts; by hand, on separate hosts, give each
// program the same --run-id and --domain and point --peer at the other hosts
// (README, "Running on several machines").
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim_coupling/session.hpp"
#include "cosim/scene_io.hpp"

namespace cosim::coupling {

// The end of a coupled process that failed: everything is on disk (the run
// flushed its outputs and told its peers), so the DDS teardown, which waits for
// acknowledgements from peers that may be dead, is skipped and the run ends
// within the time it promises.
[[noreturn]] inline void exit_after_failure(const char* program, const std::exception& e) {
  std::fprintf(stderr, "%s: error: %s\n", program, e.what());
  std::fflush(nullptr);
  std::_Exit(2);
}

// --restart and --restart-at, the same in the three programs (docs/reliability.md).
struct RestartCli {
  bool restart = false;
  long long at = -1;  // --restart-at: the checkpoint of this step (coupled: exchange)

  void add_to(CLI::App& app) {
    app.add_flag("--restart", restart, "continue the run in --out from its newest checkpoint");
    app.add_option("--restart-at", at,
                   "continue from the checkpoint of this step (a coupled run: this exchange; implies --restart)");
  }
  bool requested() const { return restart || at >= 0; }
  std::optional<std::uint64_t> step() const {
    return at >= 0 ? std::optional<std::uint64_t>(static_cast<std::uint64_t>(at)) : std::nullopt;
  }
};

struct CouplingCli {
  bool coupled = false;
  std::string vendor = "cyclone";
  std::string run_id;  // hexadecimal
  int domain = -1;     // -1: the scene's coupling.domain_id
  std::string interface = "lo";
  std::vector<std::string> peers;
  bool multicast = false;
  std::string security_dir;  // empty: an open domain

  void add_to(CLI::App& app, bool with_coupled_flag) {
    if (with_coupled_flag)
      app.add_flag("--coupled", coupled, "run as a participant of a coupled run (DDS) instead of alone");
    app.add_option("--dds", vendor, "DDS vendor of this process: fast or cyclone");
    app.add_option("--run-id", run_id, "run id shared by the processes of one run (hexadecimal)");
    app.add_option("--domain", domain, "DDS domain id (default: the scene's coupling.domain_id)");
    app.add_option("--interface", interface, "network interface or IPv4 address to use (default lo)");
    app.add_option("--peer", peers, "IPv4 address of another host of the run (unicast discovery; repeat)");
    app.add_flag("--multicast", multicast, "multicast discovery instead of --peer addresses");
    app.add_option("--security", security_dir,
                   "a secured DDS domain: the folder of scripts/make_test_ca.sh (this process uses its role's "
                   "identity in it); every process of the run must be given one");
  }

  // Throws cosim::Error for a bad vendor or run id.
  SessionOptions session(tp::Role self, const cosim::scene::Scene& scene) const {
    SessionOptions o;
    o.vendor = tp::parse_vendor(vendor);
    o.self = self;
    std::size_t used = 0;
    try {
      o.run_id = std::stoull(run_id, &used, 16);
    } catch (const std::exception&) {
      used = 0;
    }
    if (run_id.empty() || used != run_id.size() || o.run_id == 0)
      throw cosim::Error("--run-id '" + run_id + "': give the run's id as a non-zero hexadecimal number "
                         "(the same for every process of the run)");
    const auto& c = scene.coupling();
    o.transport.domain_id = domain >= 0 ? domain : c.domain_id();
    o.transport.network_interface = interface;
    if (!peers.empty()) o.transport.static_peers = peers;
    o.transport.multicast = multicast;
    o.transport.security = {security_dir, security_dir.empty() ? std::string() : tp::role_name(self)};
    o.step_timeout_s = c.step_timeout_s();
    o.start_timeout_s = c.start_timeout_s();
    return o;
  }
};

}  // namespace cosim::coupling
