#pragma once
// Starting programs as child processes: the participants of a run (launcher),
// and the helper processes of tests and benchmarks.
#include <sys/types.h>

#include <string>
#include <vector>

namespace cosim {

// Folder of the running executable (participants live beside the launcher).
std::string executable_folder();

// Where a child's standard output and error go: a file (created or truncated),
// or, if empty, the parent's. The same path for both puts both in one file.
struct ChildOutput {
  std::string stdout_path;
  std::string stderr_path;
};

// Starts `program` (argv[0]) with `args` and returns at once with its process
// id. Throws cosim::Error if it cannot be started.
pid_t start_child(const std::string& program, const std::vector<std::string>& args,
                  const ChildOutput& output = {});

// Waits for a child of start_child and returns its exit code (128 + signal if
// it was killed).
int wait_child(pid_t pid);

// As wait_child, but kills the child (SIGKILL) if it has not ended within
// `timeout_s`; it then returns 128 + SIGKILL.
int wait_child_for(pid_t pid, double timeout_s);

// Runs `program` with `args`, waits, and returns its exit code (128 + signal
// if it was killed). Throws cosim::Error if it cannot be started. While it
// waits (here and in run_children), a SIGINT or SIGTERM to this process is
// passed on to the children, which stop cleanly and report, instead of
// killing this process first.
int run_child(const std::string& program, const std::vector<std::string>& args);

// Several programs run together (the processes of a coupled run). They are
// started at once and waited for together; when one ends with an error the
// others are given `grace_s` to end by themselves (they notice within their
// own time-outs) before they are terminated (SIGTERM), and those still there
// grace_s later (a stopped or hung process) are killed (SIGKILL).
struct ChildSpec {
  std::string name;  // for messages ("tyre_fe")
  std::string program;
  std::vector<std::string> args;
  ChildOutput output = {};  // default: the parent's
};
struct ChildResult {
  std::string name;
  int exit_code = 0;          // 128 + signal if killed
  double ended_after_s = 0.0;  // since the start
  bool terminated_by_us = false;
  bool signal_forwarded = false;  // a stop signal to this process was passed on to the children
};
std::vector<ChildResult> run_children(const std::vector<ChildSpec>& children, double grace_s);

}  // namespace cosim
