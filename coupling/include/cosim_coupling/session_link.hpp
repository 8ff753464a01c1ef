#pragma once
// The coupler's link to its peers (cosim_coupling/coupled_participant.hpp) over
// its DDS session: a failure goes out as a FAILURE on the run control topic,
// naming the exchange the coupler stood at; the run's normal end is the tyre's
// to announce (it sends STOP), so a normal finish sends nothing.
#include <cstdint>
#include <string>

#include "cosim_coupling/coupled_participant.hpp"
#include "cosim_coupling/session.hpp"

namespace cosim::coupling {

class SessionLink final : public PeerLink {
 public:
  // `exchange`: the participant's count of exchanges, read when a failure is sent;
  // `who` prefixes the reason ("coupler").
  SessionLink(Session& session, const std::uint64_t& exchange, std::string who)
      : session_(session), exchange_(exchange), who_(std::move(who)) {}
  void finish(bool failed, const std::string& reason) override {
    if (failed) session_.send_failure(exchange_, who_ + ": " + reason);
  }
  void request_checkpoint_stop() override { session_.request_checkpoint_stop(); }
  std::uint64_t checkpoint_stop_exchange() const override { return session_.checkpoint_stop_exchange(); }

 private:
  Session& session_;
  const std::uint64_t& exchange_;
  std::string who_;
};

}  // namespace cosim::coupling
