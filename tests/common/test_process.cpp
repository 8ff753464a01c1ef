// The shared process spawner (common/include/cosim/process.hpp) against what
// the shell is known to do: exit codes, output redirection, signals, a time-out.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <sstream>
#include <thread>

#include "cosim/error.hpp"
#include "cosim/process.hpp"
#include "test_paths.hpp"

namespace {

using test_support::read_file;

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

// A SIGTERM to the parent alone (a scheduler's, `kill PID`) reaches the child,
// which stops as it chooses (here: exit 7 from its trap) and is waited for; the
// parent lives on. The child would otherwise sleep 20 s: the test's time bound
// is that the signal arrived, not a tuning.
TEST(Process, ASignalToTheParentIsPassedToTheChild) {
  std::thread signaller([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill(getpid(), SIGTERM);
  });
  const auto start = std::chrono::steady_clock::now();
  const int code = cosim::run_child("/bin/sh", {"-c", "trap 'kill $!; exit 7' TERM; sleep 20 & wait"});
  signaller.join();
  EXPECT_EQ(code, 7);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  // Several children: each gets it.
  std::thread again([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill(getpid(), SIGTERM);
  });
  const auto results = cosim::run_children({{"a", "/bin/sh", {"-c", "trap 'kill $!; exit 3' TERM; sleep 20 & wait"}},
                                            {"b", "/bin/sh", {"-c", "trap 'kill $!; exit 4' TERM; sleep 20 & wait"}}},
                                           10.0);
  again.join();
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].exit_code, 3);
  EXPECT_EQ(results[1].exit_code, 4);
}

}  // namespace
