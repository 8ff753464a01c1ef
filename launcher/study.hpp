#pragma once
// Participants of a scene and the study runner.
#include <string>
#include <vector>

#include "cosim/scene_io.hpp"

namespace cosim {

// The programs a scene needs: snow_sph alone for a terrain scene, tyre_fe
// alone for a tyre on a rigid road (also a coupled scene whose terrain is
// "rigid_road"), and coupler + snow_sph + tyre_fe for a tyre on an SPH terrain.
std::vector<std::string> participants(const scene::Scene& scene);

// Validates every part of a scene; throws cosim::Error listing all problems.
void check_scene(const LoadedScene& scene);

struct RunRequest {
  std::string scene_file;
  std::string out_dir;
  std::vector<std::string> sets;
  bool quiet = false;
  bool no_vtk = false;
  bool mesh_only = false;  // tyre scenes: write the meshes only
  bool restart = false;    // continue the run in out_dir from its newest checkpoint
  // Coupled scenes: when a process dies, start the run again from the newest
  // checkpoint common to all three, at most this many times (docs/reliability.md).
  int restart_on_failure = 0;
  // Coupled scenes: DDS vendor per process ("fast", "cyclone" or
  // "tyre=fast,terrain=cyclone,coupler=cyclone") and domain (-1: the scene's).
  std::string dds = "cyclone";
  int domain = -1;
  // Coupled scenes: a secured DDS domain from this folder (scripts/make_test_ca.sh);
  // empty: an open domain. docs/reliability.md, "DDS Security".
  std::string security_dir;
};
// Starts the participants of the scene and waits; returns the exit code.
int run_scene_processes(const RunRequest& request);

// The study's cases: the explicit ones, then every grid's combinations
// (labelled by their axis values joined with '_', with the axes' parameters).
std::vector<scene::StudyCase> expand_cases(const scene::Study& study);

struct StudyRequest {
  std::string study_file;
  std::string out_dir;
  bool no_vtk = false;
  // A case whose DIR/[PASS/]LABEL/summary.json says it completed with the same
  // overrides is taken as it is instead of being run again.
  bool resume = false;
  std::string pass;  // "": every pass of the study, in order
  // Run nothing: write the tables, plots and report from the runs completed in out_dir.
  bool tabulate_only = false;
  // Run only these cases (labels; empty: all). A case they depend on (a
  // derived field, a rolling radius) must be among them or completed in DIR.
  std::vector<std::string> cases;
};
// Runs the cases of a study (of one pass or of all) and writes, from every run
// completed in DIR (so a pass run later joins the earlier one's): table.csv,
// summary.json, error_vs_runtime.csv/.png, orderings.csv and
// thesis_comparison.csv when the study has them, its plots and report.html.
// If a case fails or the study is stopped, what completed is written before the
// error is reported.
int run_study(const StudyRequest& request);

}  // namespace cosim
