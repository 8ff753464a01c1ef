#pragma once
// A progress line for long runs: simulated time, steps/s, ETA. Rewrites one
// line on a terminal; prints a line every few seconds otherwise (logs, CI).
#include <chrono>
#include <cstdint>
#include <string>

namespace cosim {

class Progress {
 public:
  Progress(std::string label, double end_time_s, bool quiet = false);
  // Call every step; prints at most every `interval` of wall time. Rate and ETA
  // count from the first call, so that a run continued from a checkpoint
  // reports its own pace, not its steps before the restart over its wall time.
  void update(double sim_time_s, std::uint64_t steps);
  void finish(double sim_time_s, std::uint64_t steps);
  double elapsed_s() const;

 private:
  void print(double sim_time_s, std::uint64_t steps, bool final_line);
  std::string label_;
  double end_time_s_;
  bool quiet_, tty_;
  std::chrono::steady_clock::time_point start_, last_, first_call_;
  bool called_ = false;
  double first_time_s_ = 0.0;
  std::uint64_t first_steps_ = 0;
};

std::string format_duration(double seconds);

}  // namespace cosim
