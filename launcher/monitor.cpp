#include "monitor.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <unistd.h>

#include "cosim/error.hpp"
#include "cosim/interrupt.hpp"

namespace cosim {
namespace {

using transport::ForceSummary;
using transport::RunControl;
using transport::WheelState;

// The forces of thesis chapter 2 as the coupler publishes them: every field of
// the topic, in the IDL's order (cosim/wire_fields.hpp), shown and recorded.
struct ForceField {
  const char* name;
  double ForceSummary::*value;
};
#define COSIM_FORCE_FIELD(type, name, init) {#name, &ForceSummary::name},
constexpr ForceField kForces[] = {COSIM_WIRE_FIELDS_ForceSummary(COSIM_FORCE_FIELD)};
#undef COSIM_FORCE_FIELD
constexpr std::size_t kForceCount = sizeof(kForces) / sizeof(kForces[0]);

// Digits after the point, by the unit in the name: lengths and areas (_m, _m2)
// to 0.01 mm and 0.1 cm2, forces and moments (_N, _Nm) to 0.1.
int display_digits(const std::string& name) {
  const auto ends_with = [&](const char* unit) {
    const std::string u = unit;
    return name.size() >= u.size() && name.compare(name.size() - u.size(), u.size(), u) == 0;
  };
  return ends_with("_m") || ends_with("_m2") ? 5 : 1;
}

class CsvRecord {
 public:
  explicit CsvRecord(const std::string& path) : path_(path) {
    if (path.empty()) return;
    out_.open(path);
    if (!out_) throw Error("cosim monitor: cannot write " + path);
    out_ << "run_id,step,sim_time_s";
    for (const auto& f : kForces) out_ << ',' << f.name;
    out_ << '\n';
    out_ << std::setprecision(17);
  }
  void row(const ForceSummary& s) {
    if (!out_.is_open()) return;
    out_ << s.header.run_id << ',' << s.header.step << ',' << s.header.sim_time_s;
    for (const auto& f : kForces) out_ << ',' << s.*f.value;
    out_ << '\n';
    out_.flush();  // a recording that stops early keeps every row
  }

 private:
  std::string path_;
  std::ofstream out_;
};

void draw(std::FILE* screen, bool terminal, bool joined, const MonitorResult& r, const ForceSummary* last,
          const WheelState* wheel, const std::vector<std::deque<double>>& history) {
  std::ostringstream o;
  if (terminal) o << "\033[H\033[J";
  o << "run " << std::hex << r.run_id << std::dec << "  samples " << r.samples;
  if (r.other_run_samples) o << "  (other runs ignored: " << r.other_run_samples << ")";
  o << '\n';
  if (!last) {
    o << (joined ? "joined the run; waiting for ForceSummary samples...\n"
                 : "looking for a run on this domain (no publisher found yet)...\n");
  } else {
    o << "step " << last->header.step << "  t = " << std::fixed << std::setprecision(5)
      << last->header.sim_time_s << " s\n";
    for (std::size_t k = 0; k < kForceCount; ++k)
      o << "  " << std::left << std::setw(36) << kForces[k].name << std::right << std::setw(14)
        << std::setprecision(display_digits(kForces[k].name))
        << last->*kForces[k].value << "  " << sparkline(history[k]) << '\n';
  }
  if (wheel)
    o << std::fixed << std::setprecision(3) << "wheel: x " << wheel->rim_x_m << " m  z " << wheel->rim_z_m
      << " m  spin " << wheel->spin_rate_radps << " rad/s  torque " << std::setprecision(1)
      << wheel->applied_torque_Nm << " N m  RM2 " << wheel->reaction_moment_y_Nm << " N m\n";
  std::fputs(o.str().c_str(), screen);
  std::fflush(screen);
}

std::string format_seconds(double s) {
  std::ostringstream o;
  o << s << " s";
  return o.str();
}

}  // namespace

std::string sparkline(const std::deque<double>& values) {
  static const char* const kBlocks[] = {"\u2581", "\u2582", "\u2583", "\u2584",
                                        "\u2585", "\u2586", "\u2587", "\u2588"};
  if (values.empty()) return "";
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  std::string line;
  for (double v : values) {
    const int level = *hi > *lo ? static_cast<int>((v - *lo) / (*hi - *lo) * 7.0 + 0.5) : 0;
    line += kBlocks[std::clamp(level, 0, 7)];
  }
  return line;
}

MonitorResult run_monitor(const MonitorOptions& options, std::FILE* screen) {
  using Clock = std::chrono::steady_clock;
  auto participant = transport::make_participant(options.vendor, options.transport);
  // A deep reader history (local to this reader, compatible with the writers'
  // keep-last 16): samples wait here between screen refreshes instead of being
  // replaced, so the recording has every step the run delivered to us.
  transport::TopicQos deep = transport::default_qos<ForceSummary>();
  deep.depth = 4096;
  auto forces = participant->create_reader<ForceSummary>(deep);
  auto wheels = participant->create_reader<WheelState>();
  auto control = participant->create_reader<RunControl>();
  CsvRecord csv(options.csv_path);
  const bool terminal = isatty(fileno(screen));

  MonitorResult result;
  result.run_id = options.run_id;
  std::vector<std::deque<double>> history(kForceCount);
  ForceSummary last{};
  WheelState wheel{};
  bool have_last = false, have_wheel = false;
  auto last_sample = Clock::now(), next_draw = Clock::now();
  std::vector<ForceSummary> force_batch;
  std::vector<WheelState> wheel_batch;
  std::vector<RunControl> control_batch;
  auto same_run = [&](std::uint64_t id) {
    if (result.run_id == 0) result.run_id = id;  // follow the first run seen
    return id == result.run_id;
  };
  bool joined = false;
  while (true) {
    if (!joined && forces->matched_writers() > 0 && control->matched_writers() > 0) {
      joined = true;
      if (options.on_joined) options.on_joined();
    }
    if (interrupt_requested()) {
      result.end_reason = "interrupted";
      break;
    }
    ForceSummary sample;
    if (forces->wait_for(sample, std::chrono::milliseconds(50))) force_batch.push_back(std::move(sample));
    forces->take(force_batch);
    for (const auto& s : force_batch) {
      if (!same_run(s.header.run_id)) {
        ++result.other_run_samples;
        continue;
      }
      csv.row(s);
      for (std::size_t k = 0; k < kForceCount; ++k) {
        history[k].push_back(s.*kForces[k].value);
        if (history[k].size() > options.history) history[k].pop_front();
      }
      last = s, have_last = true, ++result.samples, last_sample = Clock::now();
      if (options.max_samples && result.samples >= options.max_samples) break;
    }
    force_batch.clear();
    wheels->take(wheel_batch);
    for (const auto& w : wheel_batch)
      if (w.header.run_id == result.run_id) wheel = w, have_wheel = true;
    wheel_batch.clear();
    control->take(control_batch);
    for (const auto& c : control_batch)
      if (c.header.run_id == result.run_id &&
          (c.kind == transport::ControlKind::stop || c.kind == transport::ControlKind::failure))
        result.end_reason = std::string(c.kind == transport::ControlKind::stop ? "run stopped" : "run failed") +
                            (c.reason.empty() ? "" : ": " + c.reason);
    control_batch.clear();
    if (options.max_samples && result.samples >= options.max_samples) result.end_reason = "max samples";
    const double idle = std::chrono::duration<double>(Clock::now() - last_sample).count();
    if (result.end_reason.empty() && options.idle_timeout_s > 0 && idle > options.idle_timeout_s)
      result.end_reason = "no sample for " + format_seconds(options.idle_timeout_s);
    if (Clock::now() >= next_draw || !result.end_reason.empty()) {
      draw(screen, terminal, joined, result, have_last ? &last : nullptr, have_wheel ? &wheel : nullptr, history);
      next_draw = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(options.refresh_s));
    }
    if (!result.end_reason.empty()) break;
  }
  return result;
}

}  // namespace cosim
