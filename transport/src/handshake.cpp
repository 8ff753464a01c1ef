// Start handshake: see cosim_transport/handshake.hpp for the protocol.
#include "cosim_transport/handshake.hpp"

#include <algorithm>

#include "cosim/error.hpp"

namespace cosim::transport {

namespace {

using Clock = std::chrono::steady_clock;

struct PeerState {
  Role role;
  bool heard = false;      // any HELLO/READY of our run from it
  bool confirmed = false;  // READY addressed to us: it has heard us
  double time_step_s = 0.0;
  std::uint64_t start_exchange = 0;
};

RunControl message(const HandshakeOptions& o, ControlKind kind, Role addressee) {
  RunControl m;
  m.header.run_id = o.run_id;
  m.header.step = o.start_exchange;
  m.kind = kind;
  m.sender = o.self;
  m.addressee = addressee;
  m.proposed_time_step_s = o.proposed_time_step_s;
  return m;
}

std::string missing_peers(const std::vector<PeerState>& peers, bool endpoints_matched) {
  std::string unheard, unconfirmed;
  for (const auto& p : peers) {
    if (!p.heard) unheard += std::string(unheard.empty() ? "" : ", ") + role_name(p.role);
    else if (!p.confirmed) unconfirmed += std::string(unconfirmed.empty() ? "" : ", ") + role_name(p.role);
  }
  std::string s;
  if (!unheard.empty()) s += "no answer from " + unheard;
  if (!unconfirmed.empty())
    s += std::string(s.empty() ? "" : "; ") + unconfirmed +
         " heard but never confirmed hearing us (or its data endpoints never matched)";
  if (!endpoints_matched) s += std::string(s.empty() ? "" : "; ") + "our own data endpoints never matched";
  return s;
}

}  // namespace

HandshakeResult handshake(Writer<RunControl>& writer, Reader<RunControl>& reader, const HandshakeOptions& o) {
  if (o.peers.empty()) throw Error("handshake: no peer roles given");
  std::vector<PeerState> peers;
  for (Role r : o.peers) {
    if (r == o.self || r == Role::any)
      throw Error(std::string("handshake: peer role '") + role_name(r) + "' is not a valid peer of '" +
                  role_name(o.self) + "'");
    peers.push_back({r});
  }
  HandshakeResult result;
  const auto start = Clock::now();
  const auto deadline = start + o.timeout;
  auto all = [&](auto pred) { return std::all_of(peers.begin(), peers.end(), pred); };
  auto send = [&](ControlKind kind, Role to) {
    writer.write(message(o, kind, to));
    ++result.messages_sent;
  };

  auto ready = [&] {
    return std::all_of(o.data_endpoints.begin(), o.data_endpoints.end(),
                       [](const Endpoint* e) { return e->matched_count() >= 1; });
  };
  auto next_send = start;
  bool local_ready = ready();
  while (!(local_ready && all([](const PeerState& p) { return p.confirmed; }))) {
    const auto now = Clock::now();
    if (now >= deadline)
      throw Error("handshake of '" + std::string(role_name(o.self)) + "' timed out after " +
                  std::to_string(o.timeout.count()) + " ms: " + missing_peers(peers, local_ready));
    if (now >= next_send) {
      local_ready = ready();
      if (!all([](const PeerState& p) { return p.heard; })) send(ControlKind::hello, Role::any);
      for (const auto& p : peers)
        if (p.heard && local_ready) send(ControlKind::ready, p.role);
      next_send = now + o.resend_period;
    }
    RunControl m;
    const auto wait = std::min(next_send, deadline) - Clock::now();
    if (!reader.wait_for(m, std::max(std::chrono::microseconds(0),
                                     std::chrono::duration_cast<std::chrono::microseconds>(wait))))
      continue;
    if (m.header.run_id != o.run_id || m.sender == o.self) continue;
    if (m.kind != ControlKind::hello && m.kind != ControlKind::ready) {
      if (m.addressee == Role::any || m.addressee == o.self) result.other_messages.push_back(std::move(m));
      continue;
    }
    auto p = std::find_if(peers.begin(), peers.end(), [&](const PeerState& s) { return s.role == m.sender; });
    if (p == peers.end()) continue;
    if (!p->heard) {
      p->heard = true;
      local_ready = ready();
      if (local_ready) send(ControlKind::ready, p->role);  // answer at once, not at the next period
    }
    p->time_step_s = m.proposed_time_step_s;
    p->start_exchange = m.header.step;
    if (m.kind == ControlKind::ready && m.addressee == o.self) p->confirmed = true;
  }
  // A peer completes on our READY; it has heard us, so its reader is matched
  // and a reliable READY reaches it once acknowledged.
  for (const auto& p : peers) send(ControlKind::ready, p.role);
  for (Endpoint* e : o.data_endpoints) e->announce();  // peers' readers know our writers now
  writer.wait_for_acknowledgments(std::chrono::milliseconds(1000));

  for (const auto& p : peers)
    if (p.start_exchange != o.start_exchange)
      throw Error(std::string("the ") + role_name(p.role) + " starts from exchange " +
                  std::to_string(p.start_exchange) + " and the " + role_name(o.self) + " from exchange " +
                  std::to_string(o.start_exchange) +
                  ": every process of a restarted run must continue from the same checkpoint (--restart-at)");
  result.agreed_time_step_s = o.proposed_time_step_s;
  for (const auto& p : peers) {
    result.peer_time_step_s.push_back(p.time_step_s);
    if (p.time_step_s > 0 && (result.agreed_time_step_s <= 0 || p.time_step_s < result.agreed_time_step_s))
      result.agreed_time_step_s = p.time_step_s;
  }
  result.elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start);
  return result;
}

}  // namespace cosim::transport
