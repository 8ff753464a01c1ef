// coupler: the synchronising hub of a coupled run (tyre_fe + terrain over DDS).
//   coupler SCENE --out DIR --run-id HEX [--dds fast|cyclone] [--domain N] [--interface IF] [--peer ADDR ...]
//           [--restart [--restart-at EXCHANGE]]
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
#include "cosim_coupling/cli.hpp"
#include "hub.hpp"

namespace {

int run_coupler(const cosim::coupling::ProgramCli& command_line) {
  const auto& scene_file = command_line.scene.scene_file;
  const auto scene = cosim::load_scene(scene_file, command_line.scene.sets);
  if (!cosim::has_fe_body(scene->message) || !scene->message.has_sph())
    throw cosim::Error(scene_file +
                       ": the coupler needs a scene with a `tyre` (or a `tread_block`) and an `sph` terrain");
  cosim::coupling::Session session(command_line.coupling.session(cosim::transport::Role::coupler, scene->message));
  try {
    const auto& restart = command_line.restart;
    const auto summary = coupler::run_hub(
        session, *scene, {command_line.scene.out_dir, command_line.scene.quiet, restart.requested(), restart.step()});
    std::printf("%s\n", summary["results"].dump(2).c_str());
    return 0;
  } catch (const std::exception& e) {
    cosim::coupling::exit_after_failure("coupler", e);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"coupler: keeps tyre_fe and the terrain in step, decides friction, decomposes the contact force"};
  cosim::coupling::ProgramCli command_line;
  command_line.add_to(app, false);
  return command_line.parse_and_run(app, argc, argv, "coupler", [&] { return run_coupler(command_line); });
}
