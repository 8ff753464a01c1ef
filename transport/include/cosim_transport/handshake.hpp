#pragma once
// Start handshake on the RunControl topic. A matched writer does not mean the
// remote reader has matched (the first lock-step sample was lost in 3 of 4
// cross-vendor runs without it), so each side re-sends until both directions
// are proven:
//   - while some peer is unheard, broadcast HELLO every resend_period;
//   - to every peer heard from (HELLO or READY), send READY addressed to it,
//     but only once our own data endpoints are matched (data_endpoints);
//   - done when every peer has sent READY addressed to us (it has heard us,
//     we have heard it, and its data endpoints are matched) and ours are
//     matched too; then one last READY to each peer, waited for until
//     acknowledged, so a peer still in its loop completes too; and each data
//     writer announces itself (Endpoint::announce) to its matched readers.
// Matching is per endpoint pair: RunControl being matched says nothing about
// the data topics, whose first volatile sample would be lost if sent to a
// reader that has not matched its writer yet. So each side lists its data
// writers and readers, and READY means all of them have matched.
// Samples of other run ids, from ourselves or addressed to other roles are
// ignored. Other kinds (START, STOP, ...) that arrive meanwhile are returned.
#include <chrono>
#include <cstdint>
#include <vector>

#include "cosim_transport/topics.hpp"
#include "cosim_transport/transport.hpp"

namespace cosim::transport {

struct HandshakeOptions {
  std::uint64_t run_id = 0;
  Role self = Role::any;
  std::vector<Role> peers;           // every role that must answer
  double proposed_time_step_s = 0.0;  // our stable step, sent with every HELLO/READY (0: none)
  std::chrono::milliseconds timeout{10000};
  std::chrono::milliseconds resend_period{50};
  // This side's data writers and readers (not the RunControl ones): each must
  // have matched at least one remote endpoint before we say READY.
  std::vector<Endpoint*> data_endpoints;
  // The exchange this process starts from (0; a restart: its checkpoint's),
  // sent in every HELLO/READY's header.step: a peer starting elsewhere is an
  // error naming both, for a run restarted from different checkpoints cannot go on.
  std::uint64_t start_exchange = 0;
};

struct HandshakeResult {
  // Peers' proposals in the order of HandshakeOptions::peers (0: none given).
  std::vector<double> peer_time_step_s;
  // Smallest positive proposal among ours and the peers' (0 if none). The
  // coupler, which hears everyone, is the one to announce it with START.
  double agreed_time_step_s = 0.0;
  int messages_sent = 0;
  std::chrono::milliseconds elapsed{0};
  std::vector<RunControl> other_messages;  // non-handshake samples of our run, in arrival order
};

// Throws cosim::Error on timeout, naming every peer role not heard from (or
// heard but that never confirmed hearing us, or our unmatched endpoints), and for a peer list that is
// empty or contains `self` or Role::any.
HandshakeResult handshake(Writer<RunControl>& writer, Reader<RunControl>& reader, const HandshakeOptions& options);

}  // namespace cosim::transport
