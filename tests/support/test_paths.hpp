#pragma once
// Paths shared by every test: the source tree, its data and scenes, and a fresh
// scratch folder per test. No solver headers, so any test can include it.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <utility>

#include "cosim/error.hpp"

#include <sys/wait.h>

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

// Folder of the built programs (COSIM_BIN_DIR, set by CTest).
inline std::string bin() {
  const char* b = std::getenv("COSIM_BIN_DIR");
  return b ? b : "build/bin";
}

// Runs a shell command; returns its exit code and its combined output.
inline std::pair<int, std::string> shell(const std::string& command) {
  std::string output;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  return {WEXITSTATUS(status), output};
}

// A file's bytes ("" if it cannot be read).
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the cosim::Error that f throws ("" if it throws none).
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const cosim::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace test_support
