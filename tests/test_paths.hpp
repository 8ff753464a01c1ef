#pragma once
// Paths shared by every test: the source tree, its data and scenes, and a fresh
// scratch folder per test. No solver headers, so any test can include it.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace test_support {

inline std::string source_dir() {
  const char* s = std::getenv("COSIM_SOURCE_DIR");
  return s ? s : ".";
}
inline std::string data_dir() { return source_dir() + "/tests/data"; }
inline std::string scene_path(const std::string& name) {
  return source_dir() + "/configs/scenes/" + name + ".textproto";
}
inline std::string scratch_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("cosim_test_" + name)).string();
}
// Empties and creates the folder; returns its path.
inline std::string scratch(const std::string& name) {
  const std::string dir = scratch_path(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace test_support
