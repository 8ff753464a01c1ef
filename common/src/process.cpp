#include "cosim/process.hpp"

#include <cerrno>
#include <cstring>
#include <csignal>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cosim/error.hpp"

#include <chrono>
#include <thread>

extern char** environ;

namespace cosim {

std::string executable_folder() {
  char buffer[4096];
  const ssize_t n = readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n <= 0) throw Error("cannot find the running executable: " + std::string(std::strerror(errno)));
  std::string path(buffer, static_cast<std::size_t>(n));
  return path.substr(0, path.find_last_of('/'));
}

int run_child(const std::string& program, const std::vector<std::string>& args) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid;
  const int rc = posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ);
  if (rc != 0) throw Error("cannot start " + program + ": " + std::strerror(rc));
  // The child gets Ctrl-C / SIGTERM itself (same process group) and stops
  // cleanly; the launcher waits for it to report instead of dying first.
  struct sigaction ignore {}, old_int {}, old_term {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGINT, &ignore, &old_int);
  sigaction(SIGTERM, &ignore, &old_term);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error("waiting for " + program + ": " + std::strerror(errno));
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

namespace {

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

}  // namespace

std::vector<ChildResult> run_children(const std::vector<ChildSpec>& children, double grace_s) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::vector<pid_t> pids(children.size(), -1);
  std::vector<ChildResult> results(children.size());
  // As in run_child: the children get Ctrl-C themselves and stop cleanly.
  struct sigaction ignore {}, old_int {}, old_term {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGINT, &ignore, &old_int);
  sigaction(SIGTERM, &ignore, &old_term);
  std::size_t running = 0;
  for (std::size_t c = 0; c < children.size(); ++c) {
    results[c].name = children[c].name;
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(children[c].program.c_str()));
    for (const auto& a : children[c].args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int rc = posix_spawn(&pids[c], children[c].program.c_str(), nullptr, nullptr, argv.data(), environ);
    if (rc != 0) {
      for (std::size_t k = 0; k < c; ++k) kill(pids[k], SIGTERM);
      for (std::size_t k = 0; k < c; ++k) waitpid(pids[k], nullptr, 0);
      sigaction(SIGINT, &old_int, nullptr);
      sigaction(SIGTERM, &old_term, nullptr);
      throw Error("cannot start " + children[c].program + ": " + std::strerror(rc));
    }
    ++running;
  }
  bool failed = false;
  Clock::time_point failed_at;
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
    if (failed && std::chrono::duration<double>(Clock::now() - failed_at).count() > grace_s) {
      for (std::size_t c = 0; c < children.size(); ++c)
        if (pids[c] > 0) kill(pids[c], SIGTERM), results[c].terminated_by_us = true;
      failed_at = Clock::now() + std::chrono::hours(1);  // once
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  return results;
}

}  // namespace cosim
