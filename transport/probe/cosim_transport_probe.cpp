// cosim_transport_probe: one side of a lock-step exchange shaped like the
// coupled scene, as its own process (see probe.hpp). Start a ping and a pong
// with the same --domain and --run-id, any vendors:
//   cosim_transport_probe --dds fast --role pong --domain 61 --run-id 42 &
//   cosim_transport_probe --dds cyclone --role ping --domain 61 --run-id 42
// Exit code 0 when every step was exchanged with the expected content.
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
#include "probe.hpp"

int main(int argc, char** argv) {
  using namespace cosim::transport;
  CLI::App app{"cosim_transport_probe: lock-step DDS exchange between two processes"};
  std::string dds = "cyclone", role = "ping", interface = "lo", security;
  probe::ProbeOptions o;
  int timeout_ms = 20000;
  app.add_option("--dds", dds, "vendor: fast or cyclone")->required();
  app.add_option("--role", role, "ping (tyre side) or pong (terrain side)")->required()->check(CLI::IsMember({"ping", "pong"}));
  app.add_option("--domain", o.transport.domain_id, "DDS domain id (0..232)")->required();
  app.add_option("--run-id", o.run_id, "run id shared by both sides")->required();
  app.add_option("--nodes", o.nodes, "surface nodes near the terrain (loads come back for a quarter)");
  app.add_option("--steps", o.steps, "timed lock-step exchanges");
  app.add_option("--warmup", o.warmup_steps, "untimed exchanges before them");
  app.add_option("--interface", interface, "network interface name or IPv4 address");
  app.add_option("--timeout-ms", timeout_ms, "handshake and per-step timeout");
  app.add_flag("!--no-check", o.check_content, "skip checking the received content");
  app.add_option("--security", security,
                 "a secured domain: the folder of scripts/make_test_ca.sh (ping uses the tyre's identity, pong the "
                 "terrain's)");
  CLI11_PARSE(app, argc, argv);
  try {
    o.vendor = parse_vendor(dds);
    o.transport.network_interface = interface;
    o.transport.security = {security, security.empty() ? "" : role == "ping" ? "tyre" : "terrain"};
    o.timeout = std::chrono::milliseconds(timeout_ms);
    if (role == "ping") {
      const probe::ProbeResult r = probe::run_ping(o);
      std::printf("ping(%s): %d steps, %d nodes, %zu B out / %zu B back per step, median %.1f us, p99 %.1f us, "
                  "rejected %llu\n",
                  dds.c_str(), r.steps, o.nodes, r.kinematics_bytes, r.loads_bytes, probe::percentile(r.step_us, 0.5),
                  probe::percentile(r.step_us, 0.99), static_cast<unsigned long long>(r.rejected));
    } else {
      const probe::ProbeResult r = probe::run_pong(o);
      std::printf("pong(%s): %d steps answered, rejected %llu\n", dds.c_str(), r.steps,
                  static_cast<unsigned long long>(r.rejected));
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cosim_transport_probe (%s, %s): error: %s\n", role.c_str(), dds.c_str(), e.what());
    return 1;
  }
}
