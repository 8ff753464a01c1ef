#include "cosim_coupling/session.hpp"

#include <algorithm>

namespace cosim::coupling {

namespace {
std::chrono::milliseconds ms(double s) { return std::chrono::milliseconds(static_cast<long long>(1000.0 * s)); }
}  // namespace

Session::Session(const SessionOptions& options)
    : options_(options),
      participant_(tp::make_participant(options.vendor, options.transport)),
      control_out_(participant_->create_writer<tp::RunControl>()),
      control_in_(participant_->create_reader<tp::RunControl>()),
      control_filter_(options.run_id) {
  if (options.run_id == 0) throw cosim::Error("a coupled run needs a non-zero run id (--run-id)");
}

Session::~Session() {
  stop_heartbeat_ = true;
  if (heartbeat_.joinable()) heartbeat_.join();
}

tp::HandshakeResult Session::join(const std::vector<tp::Role>& peers, double proposed_dt_s,
                                  const std::vector<tp::Endpoint*>& data_endpoints, std::uint64_t start_exchange) {
  tp::HandshakeOptions h;
  h.run_id = options_.run_id;
  h.self = options_.self;
  h.peers = peers;
  h.proposed_time_step_s = proposed_dt_s;
  h.timeout = ms(options_.start_timeout_s);
  h.data_endpoints = data_endpoints;
  h.start_exchange = start_exchange;
  tp::HandshakeResult r = [&] {
    std::lock_guard<std::mutex> lock(control_mutex_);
    return tp::handshake(*control_out_, *control_in_, h);
  }();
  pending_ = r.other_messages;
  const auto now = std::chrono::steady_clock::now();
  for (tp::Role peer : peers) last_heard_[peer] = now;
  heartbeat_ = std::thread([this] {
    const auto period = std::chrono::duration<double>(options_.heartbeat_period_s);
    while (!stop_heartbeat_) {
      try {
        send_control(tp::ControlKind::heartbeat, 0, "", 0.0);
      } catch (const std::exception&) {
        // A failed heartbeat is a missing heartbeat: the peers will notice.
      }
      std::this_thread::sleep_for(period);
    }
  });
  return r;
}

double Session::wait_for_start(const tp::HandshakeResult& joined) {
  (void)joined;  // its other_messages are in pending_
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + ms(options_.start_timeout_s);
  while (true) {
    for (const auto& m : pending_) {
      if (m.kind == tp::ControlKind::start && m.sender == tp::Role::coupler) {
        pending_.clear();
        return m.agreed_time_step_s;
      }
      if (m.kind == tp::ControlKind::failure)
        throw cosim::Error(std::string("the ") + tp::role_name(m.sender) + " failed before the start: " + m.reason);
      if (m.kind == tp::ControlKind::stop)
        throw cosim::Error(std::string("the ") + tp::role_name(m.sender) + " stopped the run before the start: " + m.reason);
    }
    pending_.clear();
    if (Clock::now() > deadline)
      throw cosim::Error("no START from the coupler within " + cosim::number_text(options_.start_timeout_s) + " s");
    tp::RunControl m;
    if (tp::wait_for_accepted(*control_in_, control_filter_, m, std::chrono::microseconds(100000)) &&
        m.sender != options_.self && (m.addressee == tp::Role::any || m.addressee == options_.self))
      pending_.push_back(m);
  }
}

void Session::announce_start(double agreed_dt_s, const std::string& note) {
  send_control(tp::ControlKind::start, 0, note, agreed_dt_s);
}

bool Session::control_says_stop(std::string& reason) {
  std::vector<tp::RunControl> messages;
  tp::take_accepted(*control_in_, control_filter_, messages);
  const auto now = std::chrono::steady_clock::now();
  for (const auto& m : messages) {
    if (m.sender == options_.self) continue;
    last_heard_[m.sender] = now;
    if (m.addressee != tp::Role::any && m.addressee != options_.self) continue;
    if (m.kind == tp::ControlKind::failure)
      throw cosim::Error(std::string("the ") + tp::role_name(m.sender) + " failed at step " +
                         std::to_string(m.header.step) + ": " + m.reason);
    if (m.kind == tp::ControlKind::stop) {
      reason = m.reason;
      return true;
    }
    if (m.kind == tp::ControlKind::checkpoint_request && options_.self == tp::Role::coupler)
      checkpoint_requested_ = true;
    if (m.kind == tp::ControlKind::checkpoint_at) {
      if (m.sender == tp::Role::coupler && options_.self != tp::Role::coupler) {
        checkpoint_exchange_ = m.header.step;  // named: echo it, so that the coupler goes on
        send_control(tp::ControlKind::checkpoint_at, m.header.step, "", 0.0, tp::Role::coupler);
      } else if (options_.self == tp::Role::coupler && m.header.step == checkpoint_exchange_ &&
                 std::find(checkpoint_echoes_.begin(), checkpoint_echoes_.end(), m.sender) == checkpoint_echoes_.end()) {
        checkpoint_echoes_.push_back(m.sender);
      }
    }
  }
  return false;
}

void Session::request_checkpoint_stop() {
  if (options_.self == tp::Role::coupler) {
    checkpoint_requested_ = true;
    return;
  }
  send_control(tp::ControlKind::checkpoint_request, 0, "stop signal", 0.0, tp::Role::coupler);
}

void Session::announce_checkpoint_stop(std::uint64_t exchange, const std::vector<tp::Role>& peers) {
  using Clock = std::chrono::steady_clock;
  checkpoint_exchange_ = exchange;
  checkpoint_echoes_.clear();
  send_control(tp::ControlKind::checkpoint_at, exchange, "stop at a common checkpoint", 0.0);
  const auto deadline = Clock::now() + ms(options_.step_timeout_s);
  auto all_echoed = [&] {
    for (tp::Role r : peers)
      if (std::find(checkpoint_echoes_.begin(), checkpoint_echoes_.end(), r) == checkpoint_echoes_.end()) return false;
    return true;
  };
  std::string reason;
  while (!all_echoed()) {
    if (control_says_stop(reason)) return;  // the run ended meanwhile; nothing to wait for
    for (tp::Role r : peers) check_alive(r, exchange, "echo of the checkpoint exchange");
    if (Clock::now() > deadline)
      throw cosim::Error("the solvers did not confirm the checkpoint at exchange " + std::to_string(exchange) +
                         " within " + cosim::number_text(options_.step_timeout_s) + " s");
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void Session::check_alive(tp::Role from, std::uint64_t step, const char* what) {
  const auto it = last_heard_.find(from);
  if (it == last_heard_.end()) return;
  const double silent = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second).count();
  if (silent > options_.heartbeat_timeout_s)
    throw cosim::Error(std::string("the ") + tp::role_name(from) + " process has sent nothing for " +
                       cosim::number_text(silent) + " s (no heartbeat) while we waited for its " + what +
                       " of step " + std::to_string(step) + ": it died or hangs");
}

void Session::send_control(tp::ControlKind kind, std::uint64_t step, const std::string& reason, double agreed_dt_s,
                           tp::Role addressee) {
  tp::RunControl m;
  m.header = {options_.run_id, step, 0.0};
  m.kind = kind;
  m.sender = options_.self;
  m.addressee = addressee;
  m.agreed_time_step_s = agreed_dt_s;
  m.reason = reason;
  std::lock_guard<std::mutex> lock(control_mutex_);
  control_out_->write(m);
}

void Session::send_stop(std::uint64_t step, const std::string& reason) {
  send_control(tp::ControlKind::stop, step, reason, 0.0);
  stop_heartbeat_ = true;
  std::lock_guard<std::mutex> lock(control_mutex_);
  control_out_->wait_for_acknowledgments(std::chrono::milliseconds(2000));
}

void Session::send_failure(std::uint64_t step, const std::string& reason) {
  send_control(tp::ControlKind::failure, step, reason, 0.0);
  stop_heartbeat_ = true;
  // A dead peer never acknowledges: wait only briefly for the live ones.
  std::lock_guard<std::mutex> lock(control_mutex_);
  control_out_->wait_for_acknowledgments(std::chrono::milliseconds(300));
}

void Session::count_rejections(const tp::SampleFilter& filter) {
  rejected_run_id_ += filter.rejected_run_id();
  rejected_step_ += filter.rejected_step();
}

}  // namespace cosim::coupling
