// snow_sph: the SPH terrain solver as a program.
//   snow_sph SCENE --out DIR [--set field.path=value ...] [--check] [--quiet] [--restart [--restart-at N]]
//   snow_sph SCENE --out DIR --coupled --run-id HEX [--dds fast|cyclone] [--domain N] [--interface IF] [--peer ADDR]
// (coupled: the terrain of a coupled run; docs/coupling.md)
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <CLI/CLI.hpp>

#include "cosim_coupling/cli.hpp"
#include "cosim/error.hpp"
#include "cosim/guarded_main.hpp"
#include "cosim/result_references.hpp"
#include "dds_surface_exchange.hpp"
#include "cosim/interrupt.hpp"
#include "snow_sph/run.hpp"
#include "snow_sph/scene.hpp"

int main(int argc, char** argv) {
  CLI::App app{"snow_sph: SPH terrain (snow: Drucker-Prager/Cap; water: Us-Up EOS)"};
  cosim::coupling::ProgramCli command_line;
  command_line.add_to(app, true);
  const auto& cli = command_line.scene;
  const auto& restart = command_line.restart;
  const auto& coupling = command_line.coupling;
  CLI11_PARSE(app, argc, argv);
  cosim::install_interrupt_handler();
  return cosim::guarded_main("snow_sph", [&] {
    const auto scene = snow_sph::load_sph_scene(cli.scene_file, cli.sets);
    if (cli.check) {
      std::printf("%s: ok\n", cli.scene_file.c_str());
      return 0;
    }
    coupling.require_whole_run(cli.scene_file, scene->message);
    if (coupling.coupled) {
      if (!cosim::has_fe_body(scene->message))
        throw cosim::Error(cli.scene_file + ": a coupled terrain needs a scene with a `tyre` or a `tread_block`");
      cosim::coupling::Session session(coupling.session(cosim::transport::Role::terrain, scene->message));
      snow_sph::DdsSurfaceExchange exchange(session);
      snow_sph::RunOptions options{cli.out_dir, cli.quiet, !cli.no_vtk};
      options.exchange = &exchange;
      options.restart = restart.requested(), options.restart_at = restart.step();
      return cosim::coupling::run_coupled_process("snow_sph", [&] { return snow_sph::run_scene(*scene, options); });
    }
    snow_sph::RunOptions options{cli.out_dir, cli.quiet, !cli.no_vtk};
    options.restart = restart.requested(), options.restart_at = restart.step();
    const auto summary = snow_sph::run_scene(*scene, options);
    cosim::print_results(summary);
    return 0;
  });
}
