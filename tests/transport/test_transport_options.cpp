// Vendor selection, transport option checks and the sample filter: no traffic.
#include <gtest/gtest.h>

#include <functional>

#include "cosim/error.hpp"
#include "cosim_transport/config.hpp"
#include "cosim_transport/sample_filter.hpp"
#include "cosim_transport/transport.hpp"
#include "test_paths.hpp"
#include "transport_test_support.hpp"

namespace {

using namespace cosim::transport;
using test_support::loopback;

using test_support::error_of;

TEST(TransportOptions, ParsesVendorNames) {
  for (Vendor v : available_vendors()) EXPECT_EQ(parse_vendor(vendor_name(v)), v);
  const std::string m = error_of([] { parse_vendor("opendds"); });
  EXPECT_NE(m.find("unknown DDS vendor 'opendds'"), std::string::npos) << m;
  EXPECT_NE(m.find("'fast'"), std::string::npos) << m;
  EXPECT_NE(m.find("'cyclone'"), std::string::npos) << m;
  EXPECT_THROW(parse_vendor("Fast"), cosim::Error);
  EXPECT_THROW(parse_vendor(""), cosim::Error);
}

TEST(TransportOptions, ConfigHeaderMatchesTheVendorsBuilt) {
  EXPECT_EQ(available_vendors().size(),
            static_cast<std::size_t>(COSIM_TRANSPORT_HAS_FASTDDS + COSIM_TRANSPORT_HAS_CYCLONEDDS));
  EXPECT_FALSE(available_vendors().empty());
}

TEST(TransportOptions, DefaultsStayOnLoopback) {
  const TransportOptions o;
  EXPECT_EQ(interface_address(o.network_interface), "127.0.0.1");
  EXPECT_EQ(o.static_peers, std::vector<std::string>{"127.0.0.1"});
  EXPECT_FALSE(o.multicast);
  EXPECT_EQ(o.socket_buffer_bytes, 4 * 1024 * 1024);
  EXPECT_EQ(interface_address("127.0.0.1"), "127.0.0.1");
}

TEST(TransportOptions, RefusesBadOptions) {
  TransportOptions o = loopback(180);
  o.domain_id = 233;
  EXPECT_NE(error_of([&] { validate(o); }).find("domain id must be in 0..232"), std::string::npos);
  o = loopback(180);
  o.network_interface = "no_such_if0";
  EXPECT_NE(error_of([&] { validate(o); }).find("'no_such_if0'"), std::string::npos);
  o = loopback(180);
  o.static_peers = {"localhost:7400"};
  EXPECT_NE(error_of([&] { validate(o); }).find("not an IPv4 address"), std::string::npos);
  o = loopback(180);
  o.static_peers.clear();
  EXPECT_NE(error_of([&] { validate(o); }).find("no static peers"), std::string::npos);
  o = loopback(180);
  o.socket_buffer_bytes = 0;
  EXPECT_THROW(validate(o), cosim::Error);
  for (Vendor v : available_vendors()) EXPECT_THROW(make_participant(v, o), cosim::Error);
}

TEST(SampleFilter, CountsWhatItRejects) {
  SampleFilter f(42);
  EXPECT_TRUE(f.accept({42, 0, 0.0}));
  EXPECT_FALSE(f.accept({41, 0, 0.0}));
  f.expect_step(3);
  EXPECT_FALSE(f.accept({42, 2, 0.0}));
  EXPECT_FALSE(f.accept({7, 3, 0.0}));
  EXPECT_TRUE(f.accept({42, 3, 0.0}));
  f.accept_any_step();
  EXPECT_TRUE(f.accept({42, 9, 0.0}));
  EXPECT_EQ(f.accepted(), 3u);
  EXPECT_EQ(f.rejected_run_id(), 2u);
  EXPECT_EQ(f.rejected_step(), 1u);
  EXPECT_EQ(f.rejected(), 3u);
}

TEST(RunIds, AreRandomAndNonZero) {
  const std::uint64_t a = new_run_id(), b = new_run_id();
  EXPECT_NE(a, 0u);
  EXPECT_NE(a, b);
}

}  // namespace
