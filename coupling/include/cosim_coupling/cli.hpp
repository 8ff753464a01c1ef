#pragma once
// The command-line options every program of a coupled run shares (tyre_fe,
// snow_sph, coupler): vendor, run id, domain and discovery. `cosim run` passes
// them to the processes it starts; by hand, on separate hosts, give each
// program the same --run-id and --domain and point --peer at the other hosts
// (README, "Running on several machines").
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
#include "cosim/guarded_main.hpp"
#include "cosim/interrupt.hpp"
#include "cosim/result_references.hpp"
#include "cosim/scene_io.hpp"
#include "cosim_coupling/session.hpp"

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

// A coupled process's run: its results printed; on a failure the process ends
// at once (exit_after_failure: the peers have been told, the outputs flushed).
template <class Run> int run_coupled_process(const char* program, Run run) {
  try {
    cosim::print_results(run());
    return 0;
  } catch (const std::exception& e) {
    exit_after_failure(program, e);
  }
}

// The scene, its overrides, the output folder and the progress line, the same in the
// three programs; --check and --no-vtk only in the solvers (the coupler writes no VTK
// and its scene check is the solvers').
struct SceneCli {
  std::string scene_file;
  std::string out_dir = "out";
  std::vector<std::string> sets;
  bool check = false;
  bool quiet = false;
  bool no_vtk = false;

  void add_to(CLI::App& app, bool solver) {
    app.add_option("scene", scene_file, "scene file (.textproto)")->required();
    app.add_option("--out", out_dir, "output folder");
    app.add_option("--set", sets, "override a scene field: field.path=value");
    if (solver) app.add_flag("--check", check, "validate the scene and exit");
    app.add_flag("--quiet", quiet, "no progress line");
    if (solver) app.add_flag("--no-vtk", no_vtk, "do not write VTK files");
  }
};

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
  // A solver's RunOptions: its `restart` and `restart_at`.
  template <class RunOptions>
  void apply_to(RunOptions& options) const {
    options.restart = requested();
    options.restart_at = step();
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

  // A solver started alone on a scene that couples an FE body to an SPH terrain would
  // run half of it; throws cosim::Error that says how to run the whole.
  void require_whole_run(const std::string& scene_file, const cosim::scene::Scene& scene) const {
    if (!coupled && cosim::has_fe_body(scene) && scene.has_sph() && scene.coupling().terrain() != "rigid_road")
      throw cosim::Error(scene_file + ": this scene couples an FE body to an SPH terrain; run it with `cosim run` "
                         "(or start tyre_fe, snow_sph and coupler by hand with --coupled, docs/coupling.md)");
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

// The options of a program of a coupled run, parsed in one place: the scene,
// the restart and the coupling. `solver`: tyre_fe and snow_sph (--check,
// --no-vtk, --coupled), not the coupler, which only runs coupled.
struct ProgramCli {
  SceneCli scene;
  RestartCli restart;
  CouplingCli coupling;

  void add_to(CLI::App& app, bool solver) {
    scene.add_to(app, solver);
    restart.add_to(app);
    coupling.add_to(app, solver);
  }

  // The program's main: parse the command line (CLI11's own exit on --help or a
  // bad option), take Ctrl-C as a request to stop, run `body` under guarded_main.
  int parse_and_run(CLI::App& app, int argc, char** argv, const char* program, const std::function<int()>& body) {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return app.exit(e);
    }
    cosim::install_interrupt_handler();
    return cosim::guarded_main(program, body);
  }
};

}  // namespace cosim::coupling
