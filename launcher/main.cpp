// cosim: run a scene with the participants it needs, check a scene, run a study.
//   cosim run SCENE --out DIR [--set field.path=value ...]
//   cosim check SCENE [--set ...]
//   cosim study STUDY --out DIR
#include <cstdio>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
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
  run_cmd->add_flag("--mesh-only", run.mesh_only, "tyre scenes: write the meshes and their statistics only");
  std::string check_file;
  std::vector<std::string> check_sets;
  auto* check_cmd = app.add_subcommand("check", "validate a scene without running it");
  check_cmd->add_option("scene", check_file, "scene file")->required();
  check_cmd->add_option("--set", check_sets, "override a scene field");
  std::string study_file, study_out;
  bool study_no_vtk = false;
  auto* study_cmd = app.add_subcommand("study", "run a study (several cases) and tabulate");
  study_cmd->add_option("study", study_file, "study file")->required();
  study_cmd->add_option("--out", study_out, "output folder")->required();
  study_cmd->add_flag("--no-vtk", study_no_vtk, "do not write VTK files");
  CLI11_PARSE(app, argc, argv);
  try {
    if (*run_cmd) return cosim::run_scene_processes(run);
    if (*check_cmd) {
      cosim::check_scene(*cosim::load_scene(check_file, check_sets));
      std::printf("%s: ok\n", check_file.c_str());
      return 0;
    }
    return cosim::run_study(study_file, study_out, study_no_vtk);
  } catch (const cosim::Error& e) {
    std::fprintf(stderr, "cosim: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cosim: internal error: %s\n", e.what());
    return 3;
  }
}
