// libFuzzer target: the scene loader (common/src/scene_io.cpp) on any bytes.
// Input: a scene file's text; after a line "%%", one `--set` override per line.
// The scene lies in a folder beside a copy of configs/materials, so that its
// material_file references are read and merged as a real scene's are. Every
// input must load or be refused with cosim::Error; anything else (another
// exception, a crash, a sanitizer report, a hang, unbounded memory) is a defect.
// Run: scripts/fuzz.sh (bounded) or build-fuzz/bin/fuzz_scene CORPUS (by hand).
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cosim/checkpoint.hpp"
#include "cosim/error.hpp"
#include "cosim/scene_io.hpp"

namespace {

// DIR/scenes/ for the input, DIR/materials/ the shipped materials.
std::string scene_folder() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("cosim_fuzz_scene_" + std::to_string(::getpid()));
  fs::create_directories(dir / "scenes");
  fs::remove_all(dir / "materials");
  fs::copy(fs::path(COSIM_FUZZ_SOURCE_DIR) / "configs" / "materials", dir / "materials", fs::copy_options::recursive);
  return (dir / "scenes").string();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string folder = scene_folder();
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find("\n%%\n");
  std::vector<std::string> overrides;
  if (split != std::string::npos) {
    std::size_t at = split + 4;
    while (at <= input.size()) {
      const std::size_t end = std::min(input.find('\n', at), input.size());
      if (end > at) overrides.push_back(input.substr(at, end - at));
      at = end + 1;
    }
  }
  const std::string path = folder + "/scene.textproto";
  std::ofstream(path, std::ios::binary | std::ios::trunc) << input.substr(0, split);
  try {
    const auto scene = cosim::load_scene(path, overrides);
    (void)cosim::scene_hash(scene->message);
    (void)cosim::planned_end_time_s(scene->message);
  } catch (const cosim::Error&) {
    // A bad scene is refused with a message: what the loader must do.
  }
  return 0;
}
