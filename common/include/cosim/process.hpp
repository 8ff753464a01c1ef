#pragma once
// Starting participant programs as child processes.
#include <string>
#include <vector>

namespace cosim {

// Folder of the running executable (participants live beside the launcher).
std::string executable_folder();

// Runs `program` with `args`, waits, and returns its exit code (128 + signal
// if it was killed). Throws cosim::Error if it cannot be started.
int run_child(const std::string& program, const std::vector<std::string>& args);

}  // namespace cosim
