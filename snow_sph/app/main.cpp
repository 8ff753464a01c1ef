// snow_sph: the SPH terrain solver as a program.
//   snow_sph SCENE --out DIR [--set field.path=value ...] [--check] [--quiet] [--restart [--restart-at N]]
//   snow_sph SCENE --out DIR --coupled --run-id HEX [--dds fast|cyclone] [--domain N] [--interface IF] [--peer ADDR]
// (coupled: the terrain of a coupled run; docs/coupling.md)
#include <cstdio>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
#include "cosim/result_references.hpp"
#include "cosim_coupling/cli.hpp"
#include "dds_surface_exchange.hpp"
#include "snow_sph/energy_split.hpp"
#include "snow_sph/run.hpp"
#include "snow_sph/scene.hpp"

namespace {

int run_terrain(const cosim::coupling::ProgramCli& command_line) {
  const auto& scene_file = command_line.scene.scene_file;
  const auto scene = snow_sph::load_sph_scene(scene_file, command_line.scene.sets);
  if (command_line.scene.check) {
    std::printf("%s: ok\n", scene_file.c_str());
    return 0;
  }
  const auto& coupling = command_line.coupling;
  coupling.require_whole_run(scene_file, scene->message);
  snow_sph::RunOptions options{command_line.scene.out_dir, command_line.scene.quiet, !command_line.scene.no_vtk};
  command_line.restart.apply_to(options);
  if (!coupling.coupled) {
    const nlohmann::json summary = snow_sph::run_scene(*scene, options);
    cosim::print_results(summary);
    std::printf("%s", snow_sph::terrain_energy_table(summary.value("energy", nlohmann::json())).c_str());
    return 0;
  }
  if (!cosim::has_fe_body(scene->message))
    throw cosim::Error(scene_file + ": a coupled terrain needs a scene with a `tyre` or a `tread_block`");
  cosim::coupling::Session session(coupling.session(cosim::transport::Role::terrain, scene->message));
  snow_sph::DdsSurfaceExchange exchange(session);
  options.exchange = &exchange;
  return cosim::coupling::run_coupled_process("snow_sph", [&] { return snow_sph::run_scene(*scene, options); });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"snow_sph: SPH terrain (snow: Drucker-Prager/Cap; water: Us-Up EOS)"};
  cosim::coupling::ProgramCli command_line;
  command_line.add_to(app, true);
  return command_line.parse_and_run(app, argc, argv, "snow_sph", [&] { return run_terrain(command_line); });
}
