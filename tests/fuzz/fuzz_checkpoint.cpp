// libFuzzer target: the checkpoint reader (common/src/checkpoint.cpp) on any
// bytes, as a damaged or hostile checkpoint file would give it. Every record it
// lists is read as each type; every input must be read or refused with
// cosim::Error, within memory bounded by the file's size.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "cosim/checkpoint.hpp"
#include "cosim/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("cosim_fuzz_checkpoint_" + std::to_string(::getpid()) + ".ckpt"))
          .string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), size);
  try {
    const cosim::CheckpointReader in(path);
    in.expect("snow_sph", 42);
    for (const std::string& name : in.names_with_prefix("")) {
      // Each as every type: the wrong ones must be refused by name.
      try { (void)in.get<double>(name); } catch (const cosim::Error&) {}
      try { (void)in.get<std::uint32_t>(name, 3); } catch (const cosim::Error&) {}
      try { (void)in.get_value<std::uint64_t>(name); } catch (const cosim::Error&) {}
      try { (void)in.get_text(name); } catch (const cosim::Error&) {}
    }
  } catch (const cosim::Error&) {
  }
  return 0;
}
