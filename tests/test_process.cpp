// The shared process spawner (common/include/cosim/process.hpp) against what
// the shell is known to do: exit codes, output redirection, signals, a time-out.
#include <gtest/gtest.h>

#include <csignal>
#include <chrono>
#include <fstream>
#include <sstream>

#include "cosim/error.hpp"
#include "cosim/process.hpp"
#include "test_paths.hpp"

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Process, ExitCodeAndBothStreamsInOneFile) {
  const std::string dir = test_support::scratch("process_one_file");
  const std::string log = dir + "/log.txt";
  const pid_t pid = cosim::start_child("/bin/sh", {"-c", "echo out; echo err 1>&2; exit 3"}, {log, log});
  EXPECT_EQ(cosim::wait_child(pid), 3);
  EXPECT_EQ(read_file(log), "out\nerr\n");
}

TEST(Process, SeparateStreamsAndTruncation) {
  const std::string dir = test_support::scratch("process_two_files");
  const std::string out = dir + "/out.txt", err = dir + "/err.txt";
  { std::ofstream(out) << "old content that must go\n"; }
  const pid_t pid = cosim::start_child("/bin/sh", {"-c", "echo out; echo err 1>&2"}, {out, err});
  EXPECT_EQ(cosim::wait_child(pid), 0);
  EXPECT_EQ(read_file(out), "out\n");
  EXPECT_EQ(read_file(err), "err\n");
}

TEST(Process, OnlyStderrRedirected) {
  const std::string dir = test_support::scratch("process_stderr");
  const std::string err = dir + "/err.txt";
  const pid_t pid = cosim::start_child("/bin/sh", {"-c", "echo err 1>&2"}, {"", err});
  EXPECT_EQ(cosim::wait_child(pid), 0);
  EXPECT_EQ(read_file(err), "err\n");
}

TEST(Process, KilledBySignalGives128PlusTheSignal) {
  const pid_t pid = cosim::start_child("/bin/sh", {"-c", "kill -TERM $$"});
  EXPECT_EQ(cosim::wait_child(pid), 128 + SIGTERM);
}

TEST(Process, TimeOutKillsTheChild) {
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = cosim::start_child("/bin/sleep", {"30"});
  EXPECT_EQ(cosim::wait_child_for(pid, 0.2), 128 + SIGKILL);
  // Generous bound: the wait polls every 10 ms; 10 s is far from both 0.2 s and 30 s.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  // A child that ends in time is not killed.
  EXPECT_EQ(cosim::wait_child_for(cosim::start_child("/bin/sh", {"-c", "exit 4"}), 10.0), 4);
}

TEST(Process, MissingProgramIsAnError) {
  EXPECT_THROW(cosim::start_child("/nonexistent/program", {}), cosim::Error);
  EXPECT_THROW(cosim::run_child("/nonexistent/program", {}), cosim::Error);
}

TEST(Process, RunChildWaitsForTheExitCode) {
  EXPECT_EQ(cosim::run_child("/bin/sh", {"-c", "exit 7"}), 7);
}

}  // namespace
