// coupler: the synchronising hub of a coupled run (tyre_fe + terrain over DDS).
//   coupler SCENE --out DIR --run-id HEX [--dds fast|cyclone] [--domain N] [--interface IF] [--peer ADDR ...]
//           [--restart [--restart-at EXCHANGE]]
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <CLI/CLI.hpp>

#include "cosim_coupling/cli.hpp"
#include "cosim/error.hpp"
#include "cosim/guarded_main.hpp"
#include "cosim/interrupt.hpp"
#include "hub.hpp"

int main(int argc, char** argv) {
  CLI::App app{"coupler: keeps tyre_fe and the terrain in step, decides friction, decomposes the contact force"};
  cosim::coupling::ProgramCli command_line;
  command_line.add_to(app, false);
  const auto& cli = command_line.scene;
  const auto& restart = command_line.restart;
  const auto& coupling = command_line.coupling;
  CLI11_PARSE(app, argc, argv);
  cosim::install_interrupt_handler();
  return cosim::guarded_main("coupler", [&] {
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

  });
}
