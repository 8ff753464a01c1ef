#pragma once
// Helpers of the tyre tests: run a tyre scene in-process with overrides.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/scene_io.hpp"
#include "test_paths.hpp"
#include "tyre_fe/run.hpp"
#include "tyre_fe/scene.hpp"

namespace tyre_support {

using test_support::scene_path;
using test_support::scratch;
using test_support::scratch_path;
using test_support::source_dir;

// Loads, validates and runs a tyre scene with overrides; returns summary.json.
inline nlohmann::json run(const std::string& scene_file, const std::vector<std::string>& sets,
                          const std::string& out, bool write_vtk = false) {
  const auto scene = cosim::load_scene(scene_file, sets);
  cosim::ValidationReport report;
  tyre_fe::validate_tyre_scene(*scene, report);
  report.throw_if_failed();
  return tyre_fe::run_tyre_scene(*scene, {out, true, write_vtk, false});
}

// A test's family of runs: the scene `scene_name` with the test's `sets`, one
// field (`varied_field`) set per run; each run writes into its scratch folder.
struct Variation {
  std::string scene_name;
  std::vector<std::string> sets;
  std::string varied_field;

  nlohmann::json operator()(double value, const std::string& name) const {
    auto all = sets;
    all.push_back(varied_field + "=" + std::to_string(value));
    return run(scene_path(scene_name), all, scratch(name));
  }
};

}  // namespace tyre_support
