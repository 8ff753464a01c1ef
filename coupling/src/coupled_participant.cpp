#include "cosim_coupling/coupled_participant.hpp"

#include <exception>

namespace cosim::coupling {

void report_failure(PeerLink* link, const std::string& reason) noexcept {
  if (!link) return;
  try {
    link->finish(true, reason);
  } catch (const std::exception&) {
    // The peers learn of the failure by their time-out instead.
  }
}

bool CoupledParticipant::advance() {
  if (!before_exchange()) return false;
  const bool peers_go_on = !(link_ && exchange_due()) || exchange();
  return after_exchange(peers_go_on) && peers_go_on;
}

void CoupledParticipant::finish_peers() {
  if (link_) link_->finish(false, "");
}

void CoupledParticipant::abort(const std::string& reason) noexcept {
  failed_ = true;
  on_failure(reason);
  report_failure(link_, reason);
}

bool CoupledParticipant::request_checkpoint_stop() {
  if (!link_ || !joined()) return false;
  link_->request_checkpoint_stop();
  return true;
}

std::uint64_t CoupledParticipant::checkpoint_stop_exchange() const {
  return link_ ? link_->checkpoint_stop_exchange() : 0;
}

}  // namespace cosim::coupling
