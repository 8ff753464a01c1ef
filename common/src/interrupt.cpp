#include "cosim/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace cosim {
namespace {
// The one process-wide state a signal handler may touch.
std::atomic<bool> g_interrupted{false};
extern "C" void on_signal(int) { g_interrupted.store(true); }
}  // namespace

void install_interrupt_handler() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupt_requested() { return g_interrupted.load(); }

}  // namespace cosim
