#include "cosim/progress.hpp"

#include <cstdio>
#include <unistd.h>

namespace cosim {

std::string format_duration(double s) {
  char buf[32];
  if (s < 0 || s != s) return "--";
  if (s < 60) std::snprintf(buf, sizeof buf, "%.0fs", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
  return buf;
}

Progress::Progress(std::string label, double end_time_s, bool quiet)
    : label_(std::move(label)), end_time_s_(end_time_s), quiet_(quiet), tty_(isatty(2) != 0),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

double Progress::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(double sim_time_s, std::uint64_t steps) {
  if (!called_)
    called_ = true, first_time_s_ = sim_time_s, first_steps_ = steps, first_call_ = std::chrono::steady_clock::now();
  if (quiet_ || (steps & 15u) != 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double interval = tty_ ? 0.5 : 10.0;
  if (std::chrono::duration<double>(now - last_).count() < interval) return;
  last_ = now;
  print(sim_time_s, steps, false);
}

void Progress::finish(double sim_time_s, std::uint64_t steps) {
  if (!quiet_) print(sim_time_s, steps, true);
}

void Progress::print(double t, std::uint64_t steps, bool final_line) {
  const double wall = elapsed_s();
  const double since_first_s =
      called_ ? std::chrono::duration<double>(std::chrono::steady_clock::now() - first_call_).count() : wall;
  const double done_s = t - first_time_s_;
  const double rate = since_first_s > 0 ? static_cast<double>(steps - first_steps_) / since_first_s : 0.0;
  const double eta = done_s > 0 ? since_first_s * (end_time_s_ - t) / done_s : -1.0;
  std::fprintf(stderr, "%s[%s] t = %.4g / %.4g s  step %llu  %.0f steps/s  wall %s  ETA %s%s",
               tty_ ? "\r" : "", label_.c_str(), t, end_time_s_,
               static_cast<unsigned long long>(steps), rate, format_duration(wall).c_str(),
               final_line ? "0s" : format_duration(eta).c_str(), tty_ && !final_line ? "   " : "\n");
  std::fflush(stderr);
}

}  // namespace cosim
