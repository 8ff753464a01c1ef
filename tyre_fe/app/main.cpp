// tyre_fe: the explicit FE tyre solver as a program.
//   tyre_fe SCENE --out DIR [--set field.path=value ...] [--check] [--mesh-only] [--quiet] [--no-vtk] [--restart [--restart-at N]]
//   tyre_fe SCENE --out DIR --coupled --run-id HEX [--dds fast|cyclone] [--domain N] [--interface IF] [--peer ADDR]
// (coupled: on the terrain solver of a coupled run, through the coupler; docs/coupling.md)
#include <cstdio>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
#include "cosim/result_references.hpp"
#include "cosim_coupling/cli.hpp"
#include "dds_terrain_port.hpp"
#include "tyre_fe/energy_split.hpp"
#include "tyre_fe/run.hpp"
#include "tyre_fe/scene.hpp"

namespace {

int run_tyre(const cosim::coupling::ProgramCli& command_line, bool mesh_only) {
  const auto& scene_file = command_line.scene.scene_file;
  const auto scene = cosim::load_scene(scene_file, command_line.scene.sets);
  cosim::ValidationReport report;
  tyre_fe::validate_fe_body_scene(*scene, report);
  if (!cosim::has_fe_body(scene->message)) report.fail(scene_file, "the scene has no `tyre` or `tread_block` section");
  report.throw_if_failed();
  if (command_line.scene.check) {
    std::printf("%s: ok\n", scene_file.c_str());
    return 0;
  }
  const auto& coupling = command_line.coupling;
  coupling.require_whole_run(scene_file, scene->message);
  tyre_fe::RunOptions options{command_line.scene.out_dir, command_line.scene.quiet, !command_line.scene.no_vtk,
                              mesh_only};
  command_line.restart.apply_to(options);
  if (!coupling.coupled) {
    const nlohmann::json summary = tyre_fe::run_fe_body_scene(*scene, options);
    cosim::print_results(summary);
    std::printf("%s", tyre_fe::tyre_energy_table(summary.value("energy", nlohmann::json())).c_str());
    return 0;
  }
  cosim::coupling::Session session(coupling.session(cosim::transport::Role::tyre, scene->message));
  tyre_fe::DdsTerrainPort port(session);
  options.terrain = &port;
  return cosim::coupling::run_coupled_process("tyre_fe", [&] { return tyre_fe::run_fe_body_scene(*scene, options); });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tyre_fe: explicit FE tyre (axisymmetric inflation, 3D pitch model, rigid road)"};
  cosim::coupling::ProgramCli command_line;
  command_line.add_to(app, true);
  bool mesh_only = false;
  app.add_flag("--mesh-only", mesh_only, "write the meshes and their statistics, do not solve");
  return command_line.parse_and_run(app, argc, argv, "tyre_fe", [&] { return run_tyre(command_line, mesh_only); });
}
