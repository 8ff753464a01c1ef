// The coupled participant's base (cosim_coupling/coupled_participant.hpp) on a
// participant and a link made for the test: a step calls its hooks in the order
// before_exchange -> exchange -> after_exchange, skips the exchange where none is
// due, closes the step and ends the run when a peer ended it, tells the peers of
// the run's end and of a failure once through the link, and asks for a stop at a
// checkpoint only once it has joined. Exact comparisons: strings and counts.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cosim_coupling/coupled_participant.hpp"

namespace {

struct Link final : cosim::coupling::PeerLink {
  std::vector<std::string> calls;
  void finish(bool failed, const std::string& reason) override {
    calls.push_back(failed ? "failure: " + reason : "stop");
  }
  void request_checkpoint_stop() override { calls.push_back("checkpoint"); }
  std::uint64_t checkpoint_stop_exchange() const override { return 7; }
};

// Exchanges every other step once joined; the peers end the run at step `peers_end_at`.
class Stepper final : public cosim::coupling::CoupledParticipant {
 public:
  Stepper(Link* link, int peers_end_at) : CoupledParticipant(link), peers_end_at_(peers_end_at) {}
  void join() { joined_with_window(0.5); }
  double initialize(cosim::RunRecord&) override { return 1.0; }
  double time_s() const override { return step_; }
  std::uint64_t steps() const override { return step_; }
  void output(cosim::RunRecord&) override {}
  void finalize(cosim::RunRecord&) override {}

  std::vector<std::string> log;
  int step_ = 0, peers_end_at_;

 private:
  bool before_exchange() override {
    if (step_ == 6) return false;
    log.push_back("before " + std::to_string(++step_));
    return true;
  }
  bool exchange_due() const override { return joined() && step_ % 2 == 1; }
  bool exchange() override {
    log.push_back("exchange " + std::to_string(step_));
    return step_ != peers_end_at_;
  }
  bool after_exchange(bool peers_go_on) override {
    log.push_back(std::string(peers_go_on ? "after " : "close ") + std::to_string(step_));
    return true;
  }
  void on_failure(const std::string& reason) noexcept override { log.push_back("failed: " + reason); }
};

std::vector<std::string> run(Stepper& p) {
  while (p.advance()) {
  }
  return p.log;
}

}  // namespace

TEST(CoupledParticipant, StepsThroughItsStagesAndExchangesWhereDue) {
  Link link;
  Stepper p(&link, 0);
  p.join();
  const std::vector<std::string> want{"before 1", "exchange 1", "after 1", "before 2", "after 2",
                                      "before 3", "exchange 3", "after 3", "before 4", "after 4",
                                      "before 5", "exchange 5", "after 5", "before 6", "after 6"};
  EXPECT_EQ(run(p), want);
  EXPECT_TRUE(p.coupled());
  EXPECT_EQ(p.coupling_window_s(), 0.5);
}

TEST(CoupledParticipant, WithoutALinkItNeverExchanges) {
  Stepper p(nullptr, 0);
  p.join();
  for (const auto& line : run(p)) EXPECT_EQ(line.find("exchange"), std::string::npos) << line;
  EXPECT_FALSE(p.coupled());
  EXPECT_FALSE(p.request_checkpoint_stop());
  EXPECT_EQ(p.checkpoint_stop_exchange(), 0u);
  p.finish_peers();  // nobody to tell: must not crash
  p.abort("nobody hears it");
}

TEST(CoupledParticipant, APeerEndingTheRunClosesTheStepAndEndsIt) {
  Link link;
  Stepper p(&link, 3);
  p.join();
  const std::vector<std::string> want{"before 1", "exchange 1", "after 1", "before 2",
                                      "after 2",  "before 3",   "exchange 3", "close 3"};
  EXPECT_EQ(run(p), want);
}

TEST(CoupledParticipant, TellsThePeersOnceThroughTheLink) {
  Link link;
  Stepper p(&link, 0);
  EXPECT_FALSE(p.request_checkpoint_stop());  // not joined yet: nothing to stop at
  p.join();
  EXPECT_EQ(p.coupling_window_s(), 0.5);
  EXPECT_TRUE(p.request_checkpoint_stop());
  EXPECT_EQ(p.checkpoint_stop_exchange(), 7u);
  p.finish_peers();
  p.abort("broke");
  EXPECT_EQ(link.calls, (std::vector<std::string>{"checkpoint", "stop", "failure: broke"}));
  EXPECT_EQ(p.log.back(), "failed: broke");
}
