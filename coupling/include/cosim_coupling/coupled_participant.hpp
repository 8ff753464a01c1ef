#pragma once
// A participant of a coupled run, after Chrono's co-simulation node (Serban et
// al., "Chrono::Vehicle co-simulation framework", 2019): the base owns the link
// to the peers and the exchange, the program supplies physics hooks only.
//
// One step of a coupled participant reads
//   before_exchange -> exchange -> after_exchange
// where `exchange` is the participant's exchange stage (the tyre: surface out,
// loads in; the terrain: surface in, contact, loads out; the coupler: forward
// and decompose), called only where the participant says one is due (the tyre
// exchanges at the start of a coupling window, not on its sub-steps). A
// participant without a link (a terrain on its own, a tyre on the rigid road)
// runs the same hooks with no exchange.
//
// The base also answers every coupled question of the run skeleton
// (cosim/participant.hpp) once: the peers told of the run's end or of a
// failure, the coupling window, a stop at a common checkpoint.
//
// This target depends on cosim::common alone: the solvers' libraries use it and
// never see DDS, which lives behind PeerLink's implementations in the mains.
#include <cstdint>
#include <optional>
#include <string>

#include "cosim/participant.hpp"

namespace cosim::coupling {

// What every participant's link to its peers offers, whatever it exchanges:
// the tyre's TerrainPort, the terrain's SurfaceExchange and the coupler's
// session all are one.
class PeerLink {
 public:
  virtual ~PeerLink() = default;
  // End of the run: normal stop (failed = false) or failure with a reason.
  virtual void finish(bool failed, const std::string& reason) = 0;
  // A stop signal: asks the run for a stop at a common checkpoint; the exchange
  // named for it once known (0: none yet; docs/reliability.md).
  virtual void request_checkpoint_stop() = 0;
  virtual std::uint64_t checkpoint_stop_exchange() const = 0;
};

// Tells the peers of a failure through `link` (if any); never throws: if the
// message cannot go, the peers learn of the failure by their time-out.
void report_failure(PeerLink* link, const std::string& reason) noexcept;

class CoupledParticipant : public cosim::Participant {
 public:
  // before_exchange -> exchange (when due) -> after_exchange.
  bool advance() final;
  void finish_peers() final;
  void abort(const std::string& reason) noexcept final;
  bool coupled() const final { return link_ != nullptr; }
  double coupling_window_s() const final { return window_s_ ? *window_s_ : 0.0; }
  bool request_checkpoint_stop() final;
  std::uint64_t checkpoint_stop_exchange() const final;

 protected:
  // `link`: null for a run without peers.
  explicit CoupledParticipant(PeerLink* link) : link_(link) {}
  PeerLink* link() const { return link_; }
  // The participant has joined the run with this coupling window: from now on
  // it checkpoints between windows and may ask for a stop at a checkpoint.
  void joined_with_window(double window_s) { window_s_ = window_s; }
  bool joined() const { return window_s_.has_value(); }
  // The run failed (abort was called).
  bool failed() const { return failed_; }

  // Physics hooks. before_exchange: the step's work up to its exchange; false
  // when the run is over (nothing stepped). exchange_due: whether this step
  // exchanges (default: whenever the participant has joined). exchange: the
  // exchange stage; false when a peer ended the run. after_exchange: the rest of
  // the step; `peers_go_on` is false when the exchange ended the run, and the
  // step is then only closed; returns false when the run is over.
  virtual bool before_exchange() = 0;
  virtual bool exchange_due() const { return joined(); }
  virtual bool exchange() = 0;
  virtual bool after_exchange(bool peers_go_on) = 0;
  // A failure, before the peers are told (default: nothing).
  virtual void on_failure(const std::string& reason) noexcept { (void)reason; }

 private:
  PeerLink* link_;
  std::optional<double> window_s_;
  bool failed_ = false;
};

}  // namespace cosim::coupling
