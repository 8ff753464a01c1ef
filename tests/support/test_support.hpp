#pragma once
// Helpers shared by the tests: paths and running a scene in-process.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/scene_io.hpp"
#include "test_paths.hpp"
#include "snow_sph/run.hpp"
#include "snow_sph/scene.hpp"

namespace test_support {

// Loads, validates and runs a scene with overrides; returns summary.json.
inline nlohmann::json run(const std::string& scene_file, const std::vector<std::string>& sets,
                          const std::string& out, bool write_vtk = false) {
  const auto scene = snow_sph::load_sph_scene(scene_file, sets);
  return snow_sph::run_scene(*scene, {out, true, write_vtk});
}

}  // namespace test_support
