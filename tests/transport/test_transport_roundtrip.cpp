// Every topic through every vendor pair, field by field: a writer on one
// participant, a reader on another (each of its own vendor), on loopback.
// Together with the compile-time field-count check in the Cyclone backend,
// this is what fails when idl/cosim_topics.idl and the neutral structs drift.
#include <gtest/gtest.h>

#include "cosim_transport/transport.hpp"
#include "transport_test_support.hpp"

namespace {

using namespace cosim::transport;
using namespace test_support;
using namespace std::chrono_literals;

DomainIds domains(44, 76);  // 28 pairs; the ranges of all tests: tests/CMakeLists.txt
constexpr std::uint64_t kRun = 0x5eed0123456789abULL;

class RoundTrip : public testing::TestWithParam<VendorPair> {
 protected:
  void SetUp() override {
    const int domain = domains.next();
    out_ = make_participant(GetParam().writer, loopback(domain));
    in_ = make_participant(GetParam().reader, loopback(domain));
  }
  // Writes each sample in turn and expects each back unchanged, in order.
  template <class T>
  void round_trip(const std::vector<T>& samples) {
    auto writer = out_->create_writer<T>();
    auto reader = in_->create_reader<T>();
    ASSERT_TRUE(matched_both(*writer, *reader)) << "writer and reader never matched";
    for (const T& s : samples) {
      writer->write(s);
      T got;
      ASSERT_TRUE(reader->wait_for(got, 5s)) << "sample of step " << s.header.step << " never arrived";
      expect_same(got, s);
    }
  }
  std::unique_ptr<Participant> out_, in_;
};

TEST_P(RoundTrip, SurfaceMesh) { round_trip(std::vector<SurfaceMesh>{mesh_sample(kRun, 0, 301)}); }

TEST_P(RoundTrip, SurfaceKinematics) {
  round_trip(std::vector<SurfaceKinematics>{kinematics_sample(kRun, 1, 257), kinematics_sample(kRun, 2, 0)});
}

TEST_P(RoundTrip, ContactLoads) {
  round_trip(std::vector<ContactLoads>{loads_sample(kRun, 7, 64), loads_sample(kRun, 8, 0)});
}

TEST_P(RoundTrip, WheelState) { round_trip(std::vector<WheelState>{wheel_sample(kRun, 3), wheel_sample(kRun, 4)}); }

TEST_P(RoundTrip, ForceSummary) { round_trip(std::vector<ForceSummary>{forces_sample(kRun, 5)}); }

TEST_P(RoundTrip, RunControl) {
  RunControl empty_reason = control_sample(kRun, 9);
  empty_reason.kind = ControlKind::heartbeat;
  empty_reason.sender = Role::monitor;
  empty_reason.addressee = Role::any;
  empty_reason.reason.clear();
  round_trip(std::vector<RunControl>{control_sample(kRun, 6), empty_reason});
}

// 8000 surface nodes x 6 doubles (384 KB of positions and velocities plus
// indices): fragmented into ~7 UDP datagrams of 65500 B, three steps in a row.
TEST_P(RoundTrip, LargeKinematics) {
  std::vector<SurfaceKinematics> steps;
  for (std::uint64_t s = 10; s < 13; ++s) steps.push_back(kinematics_sample(kRun, s, 8000));
  round_trip(steps);
}

INSTANTIATE_TEST_SUITE_P(Pairs, RoundTrip, testing::ValuesIn(vendor_pairs()), pair_name);

}  // namespace
