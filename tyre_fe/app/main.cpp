// tyre_fe: the explicit FE tyre solver as a program.
//   tyre_fe SCENE --out DIR [--set field.path=value ...] [--check] [--mesh-only] [--quiet] [--no-vtk] [--restart [--restart-at N]]
//   tyre_fe SCENE --out DIR --coupled --run-id HEX [--dds fast|cyclone] [--domain N] [--interface IF] [--peer ADDR]
// (coupled: on the terrain solver of a coupled run, through the coupler; docs/coupling.md)
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <CLI/CLI.hpp>

#include "cosim_coupling/cli.hpp"
#include "cosim/error.hpp"
#include "cosim/guarded_main.hpp"
#include "cosim/result_references.hpp"
#include "cosim/interrupt.hpp"
#include "tyre_fe/run.hpp"
#include "tyre_fe/scene.hpp"
#include "dds_terrain_port.hpp"

int main(int argc, char** argv) {
  CLI::App app{"tyre_fe: explicit FE tyre (axisymmetric inflation, 3D pitch model, rigid road)"};
  cosim::coupling::ProgramCli command_line;
  command_line.add_to(app, true);
  const auto& cli = command_line.scene;
  const auto& restart = command_line.restart;
  const auto& coupling = command_line.coupling;
  bool mesh_only = false;
  app.add_flag("--mesh-only", mesh_only, "write the meshes and their statistics, do not solve");
  CLI11_PARSE(app, argc, argv);
  cosim::install_interrupt_handler();
  return cosim::guarded_main("tyre_fe", [&] {
    const auto scene = cosim::load_scene(cli.scene_file, cli.sets);
    cosim::ValidationReport report;
    tyre_fe::validate_fe_body_scene(*scene, report);
    if (!cosim::has_fe_body(scene->message))
      report.fail(cli.scene_file, "the scene has no `tyre` or `tread_block` section");
    report.throw_if_failed();
    if (cli.check) {
      std::printf("%s: ok\n", cli.scene_file.c_str());
      return 0;
    }
    coupling.require_whole_run(cli.scene_file, scene->message);
    if (coupling.coupled) {
      cosim::coupling::Session session(coupling.session(cosim::transport::Role::tyre, scene->message));
      tyre_fe::DdsTerrainPort port(session);
      tyre_fe::RunOptions options{cli.out_dir, cli.quiet, !cli.no_vtk, mesh_only};
      options.terrain = &port;
      options.restart = restart.requested(), options.restart_at = restart.step();
      return cosim::coupling::run_coupled_process("tyre_fe", [&] { return tyre_fe::run_fe_body_scene(*scene, options); });
    }
    tyre_fe::RunOptions options{cli.out_dir, cli.quiet, !cli.no_vtk, mesh_only};
    options.restart = restart.requested(), options.restart_at = restart.step();
    const auto summary = tyre_fe::run_fe_body_scene(*scene, options);
    cosim::print_results(summary);
    return 0;
  });
}
