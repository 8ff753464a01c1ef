// The session of a coupled run (cosim_coupling/session.hpp) with its three
// roles in one process, one thread each, on every vendor compiled in: the start
// handshake, the heartbeat threads writing the run control topic beside the
// main loops' lock-step exchange, and the stop at a common checkpoint
// (docs/reliability.md, "Coupled runs"): the tyre asks for one; the coupler,
// at the start of an exchange s, names s + 1 and waits until both solvers have
// echoed it; every role then knows the same exchange, and no role has passed it.
// This is also the program the ThreadSanitizer build runs (scripts/sanitize.sh).
#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <thread>

#include "cosim_coupling/session.hpp"
#include "cosim_transport/sample_filter.hpp"
#include "transport_test_support.hpp"

namespace {

using namespace std::chrono_literals;
using cosim::coupling::Session;
using cosim::coupling::SessionOptions;
namespace tp = cosim::transport;

test_support::DomainIds domains(200, 209);

SessionOptions options(tp::Vendor vendor, int domain, std::uint64_t run, tp::Role self) {
  SessionOptions o;
  o.vendor = vendor;
  o.transport = test_support::loopback(domain);
  o.run_id = run;
  o.self = self;
  o.start_timeout_s = 30.0;
  o.step_timeout_s = 10.0;
  o.heartbeat_period_s = 0.01;  // often, so that the heartbeat thread writes beside every step
  return o;
}

tp::WheelState wheel(std::uint64_t run, std::uint64_t step) {
  tp::WheelState w;
  w.header = {run, step, 1e-5 * double(step)};
  return w;
}

class SessionRun : public testing::TestWithParam<tp::Vendor> {};

TEST_P(SessionRun, AStopAskedForByTheTyreIsNamedByTheCouplerAndReachedByAll) {
  const int domain = domains.next();
  const std::uint64_t run = tp::new_run_id();
  const tp::Vendor vendor = GetParam();
  constexpr std::uint64_t kAskAt = 5;   // the tyre asks after sending this step
  constexpr std::uint64_t kLimit = 40;  // no role runs past this step
  std::atomic<std::uint64_t> named_at{0};

  // Tyre: WheelState k out, ContactLoads k in; asks for the stop at step kAskAt.
  auto tyre = std::async(std::launch::async, [&] {
    Session s(options(vendor, domain, run, tp::Role::tyre));
    auto out = s.participant().create_writer<tp::WheelState>();
    auto in = s.participant().create_reader<tp::ContactLoads>();
    s.wait_for_start(s.join({tp::Role::coupler}, 2e-6, {out.get(), in.get()}));
    tp::SampleFilter filter(run);
    std::uint64_t k = 0;
    for (; k < kLimit; ++k) {
      if (s.checkpoint_stop_exchange() != 0 && k == s.checkpoint_stop_exchange()) break;
      out->write(wheel(run, k));
      if (k == kAskAt) s.request_checkpoint_stop();
      tp::ContactLoads loads;
      if (!s.wait_step(*in, filter, k, loads, "ContactLoads", tp::Role::coupler)) break;
    }
    return std::make_pair(k, s.checkpoint_stop_exchange());
  });
  // Terrain: SurfaceKinematics k in.
  auto terrain = std::async(std::launch::async, [&] {
    Session s(options(vendor, domain, run, tp::Role::terrain));
    auto in = s.participant().create_reader<tp::SurfaceKinematics>();
    s.wait_for_start(s.join({tp::Role::coupler}, 4e-6, {in.get()}));
    tp::SampleFilter filter(run);
    std::uint64_t k = 0;
    for (; k < kLimit; ++k) {
      if (s.checkpoint_stop_exchange() != 0 && k == s.checkpoint_stop_exchange()) break;
      tp::SurfaceKinematics kin;
      if (!s.wait_step(*in, filter, k, kin, "SurfaceKinematics", tp::Role::coupler)) break;
    }
    return std::make_pair(k, s.checkpoint_stop_exchange());
  });
  // Coupler: WheelState k in; names the stop once asked; then SurfaceKinematics k and ContactLoads k out.
  Session s(options(vendor, domain, run, tp::Role::coupler));
  auto wheel_in = s.participant().create_reader<tp::WheelState>();
  auto kin_out = s.participant().create_writer<tp::SurfaceKinematics>();
  auto loads_out = s.participant().create_writer<tp::ContactLoads>();
  const auto joined = s.join({tp::Role::tyre, tp::Role::terrain}, 0.0, {wheel_in.get(), kin_out.get(), loads_out.get()});
  EXPECT_EQ(joined.agreed_time_step_s, 2e-6);
  s.announce_start(2e-6, "test");
  tp::SampleFilter filter(run);
  std::uint64_t k = 0;
  for (; k < kLimit; ++k) {
    if (s.checkpoint_stop_exchange() != 0 && k == s.checkpoint_stop_exchange()) break;
    tp::WheelState w;
    ASSERT_TRUE(s.wait_step(*wheel_in, filter, k, w, "WheelState", tp::Role::tyre));
    if (s.checkpoint_stop_requested() && s.checkpoint_stop_exchange() == 0) {
      s.announce_checkpoint_stop(k + 1, {tp::Role::tyre, tp::Role::terrain});
      named_at = k + 1;
    }
    tp::SurfaceKinematics kin;
    kin.header = w.header;
    kin_out->write(kin);
    tp::ContactLoads loads;
    loads.header = w.header;
    loads_out->write(loads);
  }
  const auto [tyre_end, tyre_named] = tyre.get();
  const auto [terrain_end, terrain_named] = terrain.get();
  // Named after the request (the request travels on another topic than the
  // wheel samples, so it may be seen a step or two late), before the limit.
  ASSERT_GT(named_at.load(), kAskAt);
  ASSERT_LT(named_at.load(), kLimit);
  EXPECT_EQ(s.checkpoint_stop_exchange(), named_at.load());
  EXPECT_EQ(tyre_named, named_at.load());
  EXPECT_EQ(terrain_named, named_at.load());
  // Each stopped exactly there: it had completed that many exchanges.
  EXPECT_EQ(k, named_at.load());
  EXPECT_EQ(tyre_end, named_at.load());
  EXPECT_EQ(terrain_end, named_at.load());
}

INSTANTIATE_TEST_SUITE_P(Vendors, SessionRun, testing::ValuesIn(tp::available_vendors()),
                         test_support::vendor_param_name);

}  // namespace
