#pragma once
// Helpers of the tyre tests: run a tyre scene in-process with overrides.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/scene_io.hpp"
#include "tyre_fe/run.hpp"
#include "tyre_fe/scene.hpp"

namespace tyre_support {

inline std::string source_dir() {
  const char* s = std::getenv("COSIM_SOURCE_DIR");
  return s ? s : ".";
}
inline std::string scene_path(const std::string& name) {
  return source_dir() + "/configs/scenes/" + name + ".textproto";
}
inline std::string scratch_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("cosim_test_" + name)).string();
}
inline std::string scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("cosim_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// Loads, validates and runs a tyre scene with overrides; returns summary.json.
inline nlohmann::json run(const std::string& scene_file, const std::vector<std::string>& sets,
                          const std::string& out, bool write_vtk = false) {
  const auto scene = cosim::load_scene(scene_file, sets);
  cosim::ValidationReport report;
  tyre_fe::validate_tyre_scene(*scene, report);
  report.throw_if_failed();
  return tyre_fe::run_tyre_scene(*scene, {out, true, write_vtk, false});
}

}  // namespace tyre_support
