// coupler: the synchronising hub of a coupled run (tyre_fe + terrain over DDS).
//   coupler SCENE --out DIR --run-id HEX [--dds fast|cyclone] [--domain N] [--interface IF] [--peer ADDR ...]
//           [--restart [--restart-at EXCHANGE]]
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <CLI/CLI.hpp>

#include "cosim_coupling/cli.hpp"
#include "cosim/error.hpp"
#include "cosim/interrupt.hpp"
#include "hub.hpp"

int main(int argc, char** argv) {
  CLI::App app{"coupler: keeps tyre_fe and the terrain in step, decides friction, decomposes the contact force"};
  cosim::coupling::SceneCli cli;
  cli.add_to(app, false);
  cosim::coupling::RestartCli restart;
  restart.add_to(app);
  cosim::coupling::CouplingCli coupling;
  coupling.add_to(app, false);
  CLI11_PARSE(app, argc, argv);
  cosim::install_interrupt_handler();
  try {
    const auto scene = cosim::load_scene(cli.scene_file, cli.sets);
    if (!cosim::has_fe_body(scene->message) || !scene->message.has_sph())
      throw cosim::Error(cli.scene_file +
                         ": the coupler needs a scene with a `tyre` (or a `tread_block`) and an `sph` terrain");
    cosim::coupling::Session session(coupling.session(cosim::transport::Role::coupler, scene->message));
    try {
      const auto summary =
          coupler::run_hub(session, *scene, {cli.out_dir, cli.quiet, restart.requested(), restart.step()});
      std::printf("%s\n", summary["results"].dump(2).c_str());
      return 0;
    } catch (const std::exception& e) {
      cosim::coupling::exit_after_failure("coupler", e);
    }

  } catch (const cosim::Error& e) {
    std::fprintf(stderr, "coupler: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "coupler: internal error: %s\n", e.what());
    return 3;
  }
}
