// cosim: run a scene with the participants it needs, check a scene, run a study.
//   cosim run SCENE --out DIR [--set field.path=value ...] [--restart] [--restart-on-failure N]
//   cosim check SCENE [--set ...]
//   cosim study STUDY --out DIR [--pass NAME] [--case LABEL]... [--resume] [--tabulate]
//   cosim monitor [--dds fast|cyclone] [--domain N] [--interface IF] [--peer ADDR ...] [--csv FILE] [--security DIR]
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
#include "cosim/guarded_main.hpp"
#include "cosim/interrupt.hpp"
#include "monitor.hpp"
#include "study.hpp"

int main(int argc, char** argv) {
  CLI::App app{"cosim: tyre / snow / water co-simulation launcher"};
  app.require_subcommand(1);
  cosim::RunRequest run;
  auto* run_cmd = app.add_subcommand("run", "run a scene end to end");
  run_cmd->add_option("scene", run.scene_file, "scene file")->required();
  run_cmd->add_option("--out", run.out_dir, "output folder")->required();
  run_cmd->add_option("--set", run.sets, "override a scene field: field.path=value");
  run_cmd->add_flag("--quiet", run.quiet, "no progress line");
  run_cmd->add_flag("--no-vtk", run.no_vtk, "do not write VTK files");
  run_cmd->add_flag("--restart", run.restart,
                    "continue the run in --out from its newest checkpoint (coupled: the newest common to all three)");
  run_cmd->add_option("--restart-on-failure", run.restart_on_failure,
                      "coupled scenes: when a process dies, restart the run from its newest common checkpoint, "
                      "at most this many times");
  run_cmd->add_flag("--mesh-only", run.mesh_only, "tyre scenes: write the meshes and their statistics only");
  run_cmd->add_option("--dds", run.dds,
                      "coupled scenes: DDS vendor, for all (fast|cyclone) or per process "
                      "(tyre=fast,terrain=cyclone,coupler=cyclone)");
  run_cmd->add_option("--domain", run.domain, "coupled scenes: DDS domain id (default: the scene's coupling.domain_id)");
  run_cmd->add_option("--security", run.security_dir,
                      "coupled scenes: a secured DDS domain with the certificates and permissions in this folder "
                      "(scripts/make_test_ca.sh)");
  std::string check_file;
  std::vector<std::string> check_sets;
  auto* check_cmd = app.add_subcommand("check", "validate a scene without running it");
  check_cmd->add_option("scene", check_file, "scene file")->required();
  check_cmd->add_option("--set", check_sets, "override a scene field");
  std::string study_file, study_out, study_pass;
  std::vector<std::string> study_cases;
  bool study_no_vtk = false, study_resume = false, study_tabulate = false;
  auto* study_cmd = app.add_subcommand("study", "run a study (several cases) and tabulate");
  study_cmd->add_option("study", study_file, "study file")->required();
  study_cmd->add_option("--out", study_out, "output folder")->required();
  study_cmd->add_flag("--no-vtk", study_no_vtk, "do not write VTK files");
  study_cmd->add_flag("--resume", study_resume,
                      "keep the cases already completed in --out with the same overrides, run the others");
  study_cmd->add_flag("--tabulate", study_tabulate,
                      "run nothing: write the tables, plots and report.html from the runs completed in --out");
  study_cmd->add_option("--pass", study_pass,
                        "run one resolution pass of the study (e.g. coarse or fine); the tables join every pass completed in --out");
  study_cmd->add_option("--case", study_cases,
                        "run only this case (repeatable); the cases it depends on must be given too "
                        "or completed in --out");
  cosim::MonitorOptions monitor;
  std::string monitor_vendor = "cyclone", monitor_run_id;
  std::vector<std::string> monitor_peers;
  bool monitor_multicast = false;
  auto* monitor_cmd = app.add_subcommand("monitor", "live view of a run's force topics (join at any time)");
  monitor_cmd->add_option("--dds", monitor_vendor, "DDS vendor of this process: fast or cyclone");
  monitor_cmd->add_option("--domain", monitor.transport.domain_id, "DDS domain id of the run");
  monitor_cmd->add_option("--interface", monitor.transport.network_interface, "network interface or IPv4 address");
  monitor_cmd->add_option("--peer", monitor_peers, "IPv4 address of a host of the run (unicast discovery)");
  monitor_cmd->add_flag("--multicast", monitor_multicast, "multicast discovery instead of peers");
  monitor_cmd->add_option("--security", monitor.transport.security.directory,
                          "join a secured run with the monitor's identity in this folder (scripts/make_test_ca.sh)");
  monitor_cmd->add_option("--csv", monitor.csv_path, "record every force sample to this CSV file");
  monitor_cmd->add_option("--refresh", monitor.refresh_s, "screen refresh interval [s]");
  monitor_cmd->add_option("--run-id", monitor_run_id, "follow this run (hex); default: the first seen");
  monitor_cmd->add_option("--max-samples", monitor.max_samples, "stop after this many samples");
  monitor_cmd->add_option("--idle-timeout", monitor.idle_timeout_s, "stop after this long without samples [s]");
  CLI11_PARSE(app, argc, argv);
  return cosim::guarded_main("cosim", [&] {
    if (*run_cmd) return cosim::run_scene_processes(run);
    if (*check_cmd) {
      cosim::check_scene(*cosim::load_scene(check_file, check_sets));
      std::printf("%s: ok\n", check_file.c_str());
      return 0;
    }
    if (*monitor_cmd) {
      cosim::install_interrupt_handler();
      monitor.vendor = cosim::transport::parse_vendor(monitor_vendor);
      if (!monitor_peers.empty()) monitor.transport.static_peers = monitor_peers;
      monitor.transport.multicast = monitor_multicast;
      monitor.transport.security.identity = "monitor";
      if (!monitor_run_id.empty()) {
        std::size_t used = 0;
        try {
          monitor.run_id = std::stoull(monitor_run_id, &used, 16);
        } catch (const std::exception&) {
        }
        if (used != monitor_run_id.size() || monitor.run_id == 0)
          throw cosim::Error("--run-id '" + monitor_run_id + "' is not a hexadecimal run id");
      }
      const auto r = cosim::run_monitor(monitor, stdout);
      std::printf("cosim monitor: %s after %llu samples\n", r.end_reason.c_str(),
                  static_cast<unsigned long long>(r.samples));
      return 0;
    }
    return cosim::run_study(
        {study_file, study_out, study_no_vtk, study_resume, study_pass, study_tabulate, study_cases});
  });
}
