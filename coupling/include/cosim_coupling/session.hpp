#pragma once
// One process's place in a coupled run over DDS: its participant, the run
// control topic, the start handshake and the lock-step waits that notice a
// peer's failure or silence. Used by the three programs of a coupled run
// (tyre_fe, snow_sph, coupler); the solvers' libraries never see it.
//
// Topics of a run (docs/coupling.md): one type may travel on two channels.
//   tyre    -> coupler : SurfaceMesh (durable), SurfaceKinematics_tyre, WheelState
//   coupler -> terrain : SurfaceKinematics_terrain (with friction per facet)
//   terrain -> coupler : ContactLoads_terrain
//   coupler -> tyre    : ContactLoads_tyre;  coupler -> anyone: ForceSummary
//   everyone           : RunControl (hello/ready/start/stop/failure)
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cosim/error.hpp"
#include "cosim_transport/handshake.hpp"
#include "cosim_transport/sample_filter.hpp"
#include "cosim_transport/transport.hpp"

namespace cosim::coupling {

namespace tp = cosim::transport;

inline constexpr const char* kTyreChannel = "tyre";        // to and from the tyre
inline constexpr const char* kTerrainChannel = "terrain";  // to and from the terrain

// QoS of the per-step topic T on a channel.
template <class T> tp::TopicQos channel_qos(const char* channel) {
  tp::TopicQos q = tp::default_qos<T>();
  q.channel = channel;
  return q;
}

struct SessionOptions {
  tp::Vendor vendor = tp::Vendor::cyclone;
  tp::TransportOptions transport;
  std::uint64_t run_id = 0;
  tp::Role self = tp::Role::any;
  double step_timeout_s = 4.0;    // no sample of a step for this long: the peer hangs
  double start_timeout_s = 600.0;  // for the others to appear and say READY
  // Every process sends a HEARTBEAT every heartbeat_period_s from a thread of
  // its own once the run has started; a peer not heard for heartbeat_timeout_s
  // has died (a slow step of a large model does not look like a dead peer).
  double heartbeat_period_s = 0.25;
  double heartbeat_timeout_s = 2.0;
};

// The run ended normally (a STOP from the tyre) while we were waiting.
struct RunStopped {
  std::string reason;
};

class Session {
 public:
  explicit Session(const SessionOptions& options);
  ~Session();

  tp::Participant& participant() { return *participant_; }
  const SessionOptions& options() const { return options_; }
  std::uint64_t run_id() const { return options_.run_id; }

  // Start handshake with `peers` (this side's data endpoints must all be matched);
  // then the heartbeat starts. `start_exchange`: the exchange this process
  // continues from (0; a restart: its checkpoint's); every peer must say the same.
  tp::HandshakeResult join(const std::vector<tp::Role>& peers, double proposed_dt_s,
                           const std::vector<tp::Endpoint*>& data_endpoints, std::uint64_t start_exchange = 0);
  // Solvers: the common step announced by the coupler's START (perhaps already
  // received during the handshake).
  double wait_for_start(const tp::HandshakeResult& joined);
  // Coupler: announces the common step.
  void announce_start(double agreed_dt_s, const std::string& note);

  // Waits for the sample of `step` on `reader`, watching the run control topic:
  // returns false on a normal STOP, throws cosim::Error naming the peer, the
  // topic and the step on a FAILURE message or after step_timeout_s of silence.
  template <class T>
  bool wait_step(tp::Reader<T>& reader, tp::SampleFilter& filter, std::uint64_t step, T& out,
                 const char* what, tp::Role from, double timeout_s = 0.0);

  // Broadcasts STOP (normal end) or FAILURE with a reason, and waits briefly
  // until the peers have it.
  void send_stop(std::uint64_t step, const std::string& reason);
  void send_failure(std::uint64_t step, const std::string& reason);

  // A stop at a common checkpoint (docs/reliability.md, "Coupled runs"). Each
  // process that gets a stop signal asks for one; the coupler, at the start of
  // an exchange s, names s + 1 to every solver and waits until each has echoed
  // it (they are all waiting on the coupler's samples of s then, and cannot pass
  // s + 1 before the coupler forwards them); every process then checkpoints
  // when it has completed s + 1 exchanges and stops.
  void request_checkpoint_stop();           // a solver (or the coupler itself)
  bool checkpoint_stop_requested() const { return checkpoint_requested_; }  // coupler
  void announce_checkpoint_stop(std::uint64_t exchange, const std::vector<tp::Role>& peers);  // coupler
  // The exchange named (0: none yet).
  std::uint64_t checkpoint_stop_exchange() const { return checkpoint_exchange_; }

  // Samples dropped because of another run id or an unexpected step (all waits).
  std::uint64_t rejected_run_id() const { return rejected_run_id_; }
  std::uint64_t rejected_step() const { return rejected_step_; }
  void count_rejections(const tp::SampleFilter& filter);

 private:
  // Throws (failure) or returns a stop reason if the control topic says the run ended.
  bool control_says_stop(std::string& reason);
  // Throws if `from` has not been heard for heartbeat_timeout_s.
  void check_alive(tp::Role from, std::uint64_t step, const char* what);
  void send_control(tp::ControlKind kind, std::uint64_t step, const std::string& reason, double agreed_dt_s,
                    tp::Role addressee = tp::Role::any);

  SessionOptions options_;
  std::unique_ptr<tp::Participant> participant_;
  std::unique_ptr<tp::Writer<tp::RunControl>> control_out_;
  std::unique_ptr<tp::Reader<tp::RunControl>> control_in_;
  tp::SampleFilter control_filter_;
  std::vector<tp::RunControl> pending_;  // non-handshake control samples seen during the handshake
  std::uint64_t rejected_run_id_ = 0, rejected_step_ = 0;
  bool checkpoint_requested_ = false;
  std::uint64_t checkpoint_exchange_ = 0;
  std::vector<tp::Role> checkpoint_echoes_;  // coupler: solvers that echoed checkpoint_exchange_
  std::mutex control_mutex_;  // the heartbeat thread and the main thread share control_out_
  std::map<tp::Role, std::chrono::steady_clock::time_point> last_heard_;
  std::atomic<bool> stop_heartbeat_{false};
  std::thread heartbeat_;
};

template <class T>
bool Session::wait_step(tp::Reader<T>& reader, tp::SampleFilter& filter, std::uint64_t step, T& out,
                        const char* what, tp::Role from, double timeout_s) {
  using Clock = std::chrono::steady_clock;
  filter.expect_step(step);
  const double limit = timeout_s > 0 ? timeout_s : options_.step_timeout_s;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit));
  std::string reason;
  if (control_says_stop(reason)) return false;  // keeps the control queue short
  while (true) {
    // Short slices: the sample wakes us at once; between slices the control
    // topic is checked so that a peer's FAILURE, STOP or silence ends the wait early.
    if (tp::wait_for_accepted(reader, filter, out, std::chrono::microseconds(50000))) return true;
    if (control_says_stop(reason)) return false;
    check_alive(from, step, what);
    if (Clock::now() > deadline)
      throw cosim::Error(std::string("no ") + what + " from the " + tp::role_name(from) + " for step " +
                         std::to_string(step) + " within " + cosim::number_text(limit) +
                         " s: the " + tp::role_name(from) + " process died or stopped answering");
  }
}

}  // namespace cosim::coupling
