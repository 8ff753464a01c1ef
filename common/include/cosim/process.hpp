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

// Several programs run together (the processes of a coupled run). They are
// started at once and waited for together; when one ends with an error the
// others are given `grace_s` to end by themselves (they notice within their
// own time-outs) before they are terminated.
struct ChildSpec {
  std::string name;  // for messages ("tyre_fe")
  std::string program;
  std::vector<std::string> args;
};
struct ChildResult {
  std::string name;
  int exit_code = 0;          // 128 + signal if killed
  double ended_after_s = 0.0;  // since the start
  bool terminated_by_us = false;
};
std::vector<ChildResult> run_children(const std::vector<ChildSpec>& children, double grace_s);

}  // namespace cosim
