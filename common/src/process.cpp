#include "cosim/process.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "cosim/error.hpp"

extern char** environ;

namespace cosim {

namespace {

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

// The signal forwarded to the children: 0 until one arrives. A handler may
// touch nothing else.
std::atomic<int> g_forward{0};
extern "C" void remember_signal(int signal) { g_forward.store(signal); }

// While children run, Ctrl-C (which reaches the whole process group) and a
// SIGINT or SIGTERM sent to the parent alone (a scheduler, `kill PID`) both stop
// them cleanly: the parent does not die first but passes the signal on to the
// children it started, once, and waits for them to report. Restores the old
// handlers when it goes.
class ForwardInterrupts {
 public:
  ForwardInterrupts() {
    g_forward.store(0);
    struct sigaction forward {};
    forward.sa_handler = remember_signal;
    sigemptyset(&forward.sa_mask);
    sigaction(SIGINT, &forward, &old_int_);
    sigaction(SIGTERM, &forward, &old_term_);
  }
  ~ForwardInterrupts() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  ForwardInterrupts(const ForwardInterrupts&) = delete;
  ForwardInterrupts& operator=(const ForwardInterrupts&) = delete;
  // Sends a signal that arrived since the last call to these children (pid > 0).
  // True if one was sent.
  bool forward_to(const std::vector<pid_t>& pids) {
    const int signal = g_forward.exchange(0);
    if (signal == 0) return false;
    for (pid_t pid : pids)
      if (pid > 0) kill(pid, signal);
    return true;
  }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

}  // namespace

std::string executable_folder() {
  char buffer[4096];
  const ssize_t n = readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n <= 0) throw Error("cannot find the running executable: " + std::string(std::strerror(errno)));
  std::string path(buffer, static_cast<std::size_t>(n));
  return path.substr(0, path.find_last_of('/'));
}

pid_t start_child(const std::string& program, const std::vector<std::string>& args, const ChildOutput& output) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  constexpr int kFlags = O_WRONLY | O_CREAT | O_TRUNC;
  if (!output.stdout_path.empty())
    posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, output.stdout_path.c_str(), kFlags, 0644);
  if (!output.stderr_path.empty()) {
    if (output.stderr_path == output.stdout_path)
      posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
    else
      posix_spawn_file_actions_addopen(&files, STDERR_FILENO, output.stderr_path.c_str(), kFlags, 0644);
  }
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, program.c_str(), &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (rc != 0) throw Error("cannot start " + program + ": " + std::strerror(rc));
  return pid;
}

int wait_child(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error("waiting for process " + std::to_string(pid) + ": " + std::strerror(errno));
  }
  return exit_code_of(status);
}

int wait_child_for(pid_t pid, double timeout_s) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  while (true) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) return exit_code_of(status);
    if (r < 0 && errno != EINTR)
      throw Error("waiting for process " + std::to_string(pid) + ": " + std::strerror(errno));
    if (Clock::now() > deadline) {
      kill(pid, SIGKILL);
      return wait_child(pid);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

int run_child(const std::string& program, const std::vector<std::string>& args) {
  const pid_t pid = start_child(program, args);
  ForwardInterrupts forward;
  int status = 0;
  while (true) {  // polled: the signal may be taken by any thread of this process
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) return exit_code_of(status);
    if (r < 0 && errno != EINTR) throw Error("waiting for process " + std::to_string(pid) + ": " + std::strerror(errno));
    forward.forward_to({pid});
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

std::vector<ChildResult> run_children(const std::vector<ChildSpec>& children, double grace_s) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::vector<pid_t> pids(children.size(), -1);
  std::vector<ChildResult> results(children.size());
  ForwardInterrupts forward;
  std::size_t running = 0;
  for (std::size_t c = 0; c < children.size(); ++c) {
    results[c].name = children[c].name;
    try {
      pids[c] = start_child(children[c].program, children[c].args, children[c].output);
    } catch (const Error&) {
      for (std::size_t k = 0; k < c; ++k) kill(pids[k], SIGTERM);
      for (std::size_t k = 0; k < c; ++k) waitpid(pids[k], nullptr, 0);
      throw;
    }
    ++running;
  }
  bool failed = false, terminated = false, killed = false;
  Clock::time_point failed_at, terminated_at;
  while (running > 0) {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0) {
      for (std::size_t c = 0; c < children.size(); ++c) {
        if (pids[c] != pid) continue;
        results[c].exit_code = exit_code_of(status);
        results[c].ended_after_s = std::chrono::duration<double>(Clock::now() - start).count();
        pids[c] = -1;
        --running;
        if (results[c].exit_code != 0 && !failed) failed = true, failed_at = Clock::now();
      }
      continue;
    }
    if (pid < 0 && errno != EINTR) break;
    if (forward.forward_to(pids))
      for (auto& r : results) r.signal_forwarded = true;
    if (failed && !terminated && std::chrono::duration<double>(Clock::now() - failed_at).count() > grace_s) {
      for (std::size_t c = 0; c < children.size(); ++c)
        if (pids[c] > 0) kill(pids[c], SIGTERM), results[c].terminated_by_us = true;
      terminated = true, terminated_at = Clock::now();
    }
    // A child that SIGTERM cannot end (stopped with SIGSTOP, hung in a system
    // call with the signal blocked) is killed after another grace period.
    if (terminated && !killed && std::chrono::duration<double>(Clock::now() - terminated_at).count() > grace_s) {
      for (std::size_t c = 0; c < children.size(); ++c)
        if (pids[c] > 0) kill(pids[c], SIGKILL);
      killed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return results;
}

}  // namespace cosim
