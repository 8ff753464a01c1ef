#pragma once
// cosim monitor: a live view of a run's force topics (ForceSummary, WheelState,
// RunControl) from any terminal or host on the same DDS domain. It only reads,
// so it can join a run already under way and leave without disturbing it.
#include <cstdint>
#include <cstdio>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "cosim_transport/transport.hpp"

namespace cosim {

struct MonitorOptions {
  transport::Vendor vendor = transport::Vendor::cyclone;
  transport::TransportOptions transport;
  std::string csv_path;           // empty: no recording
  double refresh_s = 0.5;         // screen refresh interval (wall time)
  std::size_t history = 24;       // samples kept per force for the sparkline
  std::uint64_t run_id = 0;       // 0: follow the first run seen
  std::uint64_t max_samples = 0;  // stop after this many force samples (0: no limit)
  double idle_timeout_s = 0.0;    // stop after this long without a sample (0: never)
  // Called once when the force and control readers have discovered a publisher.
  std::function<void()> on_joined;
};

struct MonitorResult {
  std::uint64_t run_id = 0;
  std::uint64_t samples = 0;            // force summaries shown and recorded
  std::uint64_t other_run_samples = 0;  // ignored: another run on the domain
  std::string end_reason;               // "max samples", "run stopped: ...", "idle", "interrupted"
};

// Unicode block sparkline of `values` scaled between their minimum and maximum.
std::string sparkline(const std::deque<double>& values);

// Runs until one of the stop conditions of `options`; draws on `screen` (redrawn
// in place when it is a terminal). Throws cosim::Error if the CSV cannot be written.
MonitorResult run_monitor(const MonitorOptions& options, std::FILE* screen);

}  // namespace cosim
