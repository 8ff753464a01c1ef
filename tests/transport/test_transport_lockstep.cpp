// Lock-step behaviour on every vendor pair: a late joiner gets the durable
// SurfaceMesh, 200 steps of ping-pong lose nothing, samples of another run or
// an unexpected step are dropped and counted; and the start handshake (agreed
// time step, timeout naming the missing role) on each vendor.
#include <gtest/gtest.h>

#include "test_paths.hpp"

#include <future>

#include "cosim/error.hpp"
#include "cosim_transport/handshake.hpp"
#include "cosim_transport/sample_filter.hpp"
#include "cosim_transport/transport.hpp"
#include "probe.hpp"
#include "transport_test_support.hpp"

namespace {

using namespace cosim::transport;
using namespace test_support;
using namespace std::chrono_literals;

DomainIds domains(80, 149);

class LockStep : public testing::TestWithParam<VendorPair> {};

TEST_P(LockStep, LateJoinerGetsTheDurableSurfaceMesh) {
  const int domain = domains.next();
  const std::uint64_t run = new_run_id();
  auto tyre = make_participant(GetParam().writer, loopback(domain));
  auto mesh_out = tyre->create_writer<SurfaceMesh>();
  const SurfaceMesh first = mesh_sample(run, 0, 50);
  SurfaceMesh latest = mesh_sample(run, 0, 120);  // keep-last 1: only this one is kept
  latest.header.step = 1;
  mesh_out->write(first);
  mesh_out->write(latest);

  // The terrain joins afterwards, with nothing matched when the mesh was written.
  auto terrain = make_participant(GetParam().reader, loopback(domain));
  auto mesh_in = terrain->create_reader<SurfaceMesh>();
  SurfaceMesh got;
  ASSERT_TRUE(mesh_in->wait_for(got, 10s)) << "the late joiner never got the mesh";
  expect_same(got, latest);
  std::vector<SurfaceMesh> more;
  EXPECT_EQ(mesh_in->take(more), 0u) << "keep-last 1 should deliver only the latest mesh";
}

// The probe's exchange in two threads: handshake, durable mesh, then 200 steps
// of kinematics out / loads back, each step's content checked exactly.
TEST_P(LockStep, PingPong200StepsWithoutLoss) {
  probe::ProbeOptions ping, pong;
  ping.transport = pong.transport = loopback(domains.next());
  ping.run_id = pong.run_id = new_run_id();
  ping.vendor = GetParam().writer;
  pong.vendor = GetParam().reader;
  ping.nodes = pong.nodes = 800;
  ping.steps = pong.steps = 200;
  ping.timeout = pong.timeout = 10s;
  auto pong_done = std::async(std::launch::async, [&] { return probe::run_pong(pong); });
  const probe::ProbeResult r = probe::run_ping(ping);
  const probe::ProbeResult p = pong_done.get();
  EXPECT_EQ(r.steps, 200);
  EXPECT_EQ(p.steps, 200);
  EXPECT_EQ(r.rejected, 0u);
  EXPECT_EQ(p.rejected, 0u);
}

TEST_P(LockStep, SamplesOfAnotherRunOrStepAreRejected) {
  const int domain = domains.next();
  const std::uint64_t ours = new_run_id(), stale = ours ^ 0xffULL;
  auto a = make_participant(GetParam().writer, loopback(domain));
  auto b = make_participant(GetParam().reader, loopback(domain));
  auto out = a->create_writer<WheelState>();
  auto in = b->create_reader<WheelState>();
  ASSERT_TRUE(matched_both(*out, *in));
  // A stale process of an earlier run still publishes on the domain, and a
  // sample of a step we are not waiting for arrives first.
  for (std::uint64_t s = 0; s < 3; ++s) out->write(wheel_sample(stale, s + 1));
  out->write(wheel_sample(ours, 5));
  out->write(wheel_sample(ours, 1));

  SampleFilter filter(ours);
  filter.expect_step(1);
  WheelState got;
  ASSERT_TRUE(wait_for_accepted(*in, filter, got, 5s));
  expect_same(got, wheel_sample(ours, 1));
  EXPECT_EQ(filter.rejected_run_id(), 3u);
  EXPECT_EQ(filter.rejected_step(), 1u);
  EXPECT_EQ(filter.accepted(), 1u);

  // Nothing else of ours arrives: waiting again times out, and take drops the stale ones.
  out->write(wheel_sample(stale, 2));
  filter.expect_step(2);
  EXPECT_FALSE(wait_for_accepted(*in, filter, got, 300ms));
  EXPECT_EQ(filter.rejected_run_id(), 4u);
  out->write(wheel_sample(stale, 3));
  out->write(wheel_sample(ours, 2));
  std::vector<WheelState> accepted;
  ASSERT_TRUE(eventually([&] { return take_accepted(*in, filter, accepted) > 0 || !accepted.empty(); }, 5000ms));
  ASSERT_EQ(accepted.size(), 1u);
  EXPECT_EQ(accepted[0].header.step, 2u);
}

// Both sides propose a step; each learns the other's and agrees on the smaller.
TEST_P(LockStep, HandshakeAgreesOnTheSmallerTimeStep) {
  const int domain = domains.next();
  const std::uint64_t run = new_run_id();
  auto tyre = make_participant(GetParam().writer, loopback(domain));
  auto terrain = make_participant(GetParam().reader, loopback(domain));
  auto side = [&](Participant& p, Role self, Role peer, double dt) {
    auto w = p.create_writer<RunControl>();
    auto r = p.create_reader<RunControl>();
    HandshakeOptions o{run, self, {peer}, dt, 10s};
    return handshake(*w, *r, o);
  };
  auto terrain_done = std::async(std::launch::async, [&] { return side(*terrain, Role::terrain, Role::tyre, 4e-6); });
  const HandshakeResult t = side(*tyre, Role::tyre, Role::terrain, 2.5e-6);
  const HandshakeResult s = terrain_done.get();
  EXPECT_EQ(t.agreed_time_step_s, 2.5e-6);
  EXPECT_EQ(s.agreed_time_step_s, 2.5e-6);
  ASSERT_EQ(t.peer_time_step_s.size(), 1u);
  EXPECT_EQ(t.peer_time_step_s[0], 4e-6);
  EXPECT_EQ(s.peer_time_step_s[0], 2.5e-6);
}

// A restarted run whose processes continue from different checkpoints cannot
// go on: each side learns the other's starting exchange and refuses, naming both.
TEST_P(LockStep, HandshakeRefusesPeersStartingFromDifferentExchanges) {
  const int domain = domains.next();
  const std::uint64_t run = new_run_id();
  auto tyre = make_participant(GetParam().writer, loopback(domain));
  auto coupler = make_participant(GetParam().reader, loopback(domain));
  auto side = [&](Participant& p, Role self, Role peer, std::uint64_t start) {
    auto w = p.create_writer<RunControl>();
    auto r = p.create_reader<RunControl>();
    HandshakeOptions o{run, self, {peer}, 1e-6, 10s};
    o.start_exchange = start;
    return test_support::error_of([&] { handshake(*w, *r, o); });
  };
  auto coupler_error = std::async(std::launch::async, [&] { return side(*coupler, Role::coupler, Role::tyre, 892); });
  const std::string tyre_error = side(*tyre, Role::tyre, Role::coupler, 446);
  EXPECT_NE(tyre_error.find("the coupler starts from exchange 892 and the tyre from exchange 446"), std::string::npos)
      << tyre_error;
  const std::string c = coupler_error.get();
  EXPECT_NE(c.find("the tyre starts from exchange 446 and the coupler from exchange 892"), std::string::npos) << c;
}

INSTANTIATE_TEST_SUITE_P(Pairs, LockStep, testing::ValuesIn(vendor_pairs()), pair_name);

class Handshake : public testing::TestWithParam<Vendor> {};

TEST_P(Handshake, TimeoutNamesTheRoleNotFound) {
  auto coupler = make_participant(GetParam(), loopback(domains.next()));
  auto w = coupler->create_writer<RunControl>();
  auto r = coupler->create_reader<RunControl>();
  HandshakeOptions o{new_run_id(), Role::coupler, {Role::tyre, Role::terrain}, 0.0, 300ms};
  try {
    handshake(*w, *r, o);
    FAIL() << "handshake without peers should time out";
  } catch (const cosim::Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("timed out"), std::string::npos) << m;
    EXPECT_NE(m.find("no answer from tyre, terrain"), std::string::npos) << m;
  }
}

TEST_P(Handshake, RefusesBadPeerLists) {
  auto p = make_participant(GetParam(), loopback(domains.next()));
  auto w = p->create_writer<RunControl>();
  auto r = p->create_reader<RunControl>();
  EXPECT_THROW(handshake(*w, *r, HandshakeOptions{1, Role::tyre, {}, 0.0, 100ms}), cosim::Error);
  EXPECT_THROW(handshake(*w, *r, HandshakeOptions{1, Role::tyre, {Role::tyre}, 0.0, 100ms}), cosim::Error);
  EXPECT_THROW(handshake(*w, *r, HandshakeOptions{1, Role::tyre, {Role::any}, 0.0, 100ms}), cosim::Error);
}

INSTANTIATE_TEST_SUITE_P(Vendors, Handshake, testing::ValuesIn(available_vendors()), vendor_param_name);

}  // namespace
