// Lock-step exchange cost per step over DDS on loopback, for every vendor pair:
// kinematics of N surface nodes (and N facets' friction) out, sparse loads of
// N/4 nodes (and N/4 facets) back, as the coupled scene will exchange them.
//   exchange_bench [--nodes N] [--steps S] [--warmup W] [--domain D] [--pair fast:cyclone ...]
// The tyre side runs here; the terrain side is a cosim_transport_probe process
// (pong) started beside it, so every step crosses processes. Prints, per pair,
// the median and 99th percentile of the write-to-loads time (microseconds).
#include <csignal>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
#include "cosim/process.hpp"
#include "probe.hpp"

namespace {

using namespace cosim::transport;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"exchange_bench: lock-step DDS exchange cost per step, every vendor pair"};
  probe::ProbeOptions o;
  o.nodes = 5000;
  o.steps = 2000;
  o.warmup_steps = 200;
  o.check_content = false;
  int domain = 200;
  std::vector<std::string> only;
  app.add_option("--nodes", o.nodes, "surface nodes near the terrain (loads come back for N/4)");
  app.add_option("--steps", o.steps, "timed steps per pair");
  app.add_option("--warmup", o.warmup_steps, "untimed steps first");
  app.add_option("--domain", domain, "first DDS domain id (one per pair)");
  app.add_option("--pair", only, "only these pairs, e.g. fast:cyclone (default: all)");
  CLI11_PARSE(app, argc, argv);
  try {
    const std::string probe_exe = cosim::executable_folder() + "/cosim_transport_probe";
    std::printf("exchange_bench: %d nodes out, %d back, %d steps (+%d warm-up) per pair, loopback, separate processes\n",
                o.nodes, o.nodes / 4, o.steps, o.warmup_steps);
    std::printf("%-18s %10s %10s %11s %11s %11s\n", "tyre -> terrain", "bytes out", "bytes back", "median_us",
                "p99_us", "max_us");
    for (Vendor ping : available_vendors()) {
      for (Vendor pong : available_vendors()) {
        const std::string key = std::string(vendor_name(ping)) + ":" + vendor_name(pong);
        if (!only.empty() && std::find(only.begin(), only.end(), key) == only.end()) continue;
        o.vendor = ping;
        o.run_id = new_run_id();
        o.transport.domain_id = domain++;
        // The pong's own summary line is not wanted here.
        const pid_t child = cosim::start_child(
            probe_exe,
            {"--dds", vendor_name(pong), "--role", "pong", "--domain", std::to_string(o.transport.domain_id),
             "--run-id", std::to_string(o.run_id), "--nodes", std::to_string(o.nodes), "--steps",
             std::to_string(o.steps), "--warmup", std::to_string(o.warmup_steps), "--no-check"},
            {"/dev/null", ""});
        probe::ProbeResult r;
        try {
          r = probe::run_ping(o);
        } catch (...) {
          kill(child, SIGTERM);
          cosim::wait_child(child);
          throw;
        }
        if (cosim::wait_child(child) != 0) throw cosim::Error("the pong process failed");
        const std::string pair = std::string(vendor_name(ping)) + " -> " + vendor_name(pong);
        std::printf("%-18s %10zu %10zu %11.1f %11.1f %11.1f\n", pair.c_str(), r.kinematics_bytes, r.loads_bytes,
                    probe::percentile(r.step_us, 0.5), probe::percentile(r.step_us, 0.99),
                    probe::percentile(r.step_us, 1.0));
        std::fflush(stdout);
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exchange_bench: error: %s\n", e.what());
    return 1;
  }
}
