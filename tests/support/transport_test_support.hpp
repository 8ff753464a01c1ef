#pragma once
// Shared by the transport tests, which are written once and run on every
// vendor pair compiled in (fast->fast, cyclone->cyclone, fast->cyclone,
// cyclone->fast): the pairs, loopback-only options with one DDS domain per
// test (so test programs run in parallel never cross-talk), a sample of every
// topic with every field set to a distinct value, and field-by-field checks.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "cosim_transport/transport.hpp"

namespace test_support {

using namespace cosim::transport;

struct VendorPair {
  Vendor writer;
  Vendor reader;
};

inline std::vector<VendorPair> vendor_pairs() {
  std::vector<VendorPair> pairs;
  for (Vendor w : available_vendors())
    for (Vendor r : available_vendors()) pairs.push_back({w, r});
  return pairs;
}

inline std::string pair_name(const testing::TestParamInfo<VendorPair>& info) {
  return std::string(vendor_name(info.param.writer)) + "_to_" + vendor_name(info.param.reader);
}
inline std::string vendor_param_name(const testing::TestParamInfo<Vendor>& info) { return vendor_name(info.param); }

// A fresh domain id per call, from `first` up (each test program has its own
// range: roundtrip 10-79, lockstep 80-149, processes 150-179, options 180-189,
// monitor 190-199, session 200-209, security 210-230; the benchmark uses 200-232).
class DomainIds {
 public:
  explicit DomainIds(int first, int last) : next_(first), last_(last) {}
  int next() {
    if (next_ > last_) throw std::runtime_error("test program ran out of its DDS domain ids");
    return next_++;
  }

 private:
  int next_, last_;
};

// Everything on loopback: lo, unicast discovery to 127.0.0.1, no multicast.
inline TransportOptions loopback(int domain_id) {
  TransportOptions o;
  o.domain_id = domain_id;
  o.network_interface = "lo";
  o.static_peers = {"127.0.0.1"};
  o.multicast = false;
  return o;
}

// Polls `done` until true or the timeout passes.
template <class Pred>
bool eventually(Pred done, std::chrono::milliseconds timeout = std::chrono::milliseconds(10000)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

// Writer and reader have matched each other (both sides of the pair); then the
// writer announces itself, as the start handshake does for data endpoints.
template <class T>
bool matched_both(Writer<T>& w, const Reader<T>& r) {
  if (!eventually([&] { return w.matched_readers() >= 1 && r.matched_writers() >= 1; })) return false;
  w.announce();
  return true;
}

// Distinct values: field f, entry i, offset by the step.
inline std::vector<double> doubles(std::size_t n, int f, std::uint64_t step = 0) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = f * 1.0e3 + 1.0e-3 * static_cast<double>(step) + 1.0e-7 * i - 0.5;
  return v;
}
inline std::vector<std::uint32_t> ids(std::size_t n, std::uint32_t base) {
  std::vector<std::uint32_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = base + static_cast<std::uint32_t>(7 * i);
  return v;
}
inline SampleHeader header(std::uint64_t run_id, std::uint64_t step) {
  return {run_id, step, 1.25e-6 * static_cast<double>(step) + 3.0};
}

// Distinct values in every field of a topic, expanded from the table
// (cosim/wire_fields.hpp), so that a field added to the IDL and the table is
// filled and compared through every vendor pair without a line here. Field f's
// array has n + f entries (none when n is 0), so that a conversion that sizes
// one array by another's length is caught.
struct SampleFill {
  std::size_t n;
  std::uint64_t step;
  int field = 0;

  std::size_t size() const { return n == 0 ? 0 : n + static_cast<std::size_t>(field); }
  void operator()(std::vector<double>& v) { ++field, v = doubles(size(), field, step); }
  void operator()(std::vector<std::uint32_t>& v) {
    ++field, v = ids(size(), 1000u * static_cast<std::uint32_t>(field));
  }
  void operator()(std::vector<cosim::FacetTag>& v) {
    ++field;
    v.clear();
    for (std::size_t i = 0; i < size(); ++i) v.push_back(static_cast<cosim::FacetTag>(i % cosim::kFacetTagCount));
  }
  void operator()(double& v) { ++field, v = 0.125 * field + 1.0e-3 * static_cast<double>(step) - 40.5; }
};
#define COSIM_FILL_FIELD(type, name, init) fill(sample.name);
#define COSIM_SAMPLE(T, function)                                                  \
  inline T function(std::uint64_t run_id, std::uint64_t step, std::size_t n = 3) { \
    T sample;                                                                      \
    sample.header = header(run_id, step);                                          \
    SampleFill fill{n, step};                                                      \
    COSIM_WIRE_FIELDS_##T(COSIM_FILL_FIELD) return sample;                         \
  }
COSIM_SAMPLE(SurfaceMesh, mesh_sample)
COSIM_SAMPLE(SurfaceKinematics, kinematics_sample)
COSIM_SAMPLE(ContactLoads, loads_sample)
COSIM_SAMPLE(WheelState, wheel_sample)
COSIM_SAMPLE(ForceSummary, forces_sample)
#undef COSIM_SAMPLE
#undef COSIM_FILL_FIELD
inline RunControl control_sample(std::uint64_t run_id, std::uint64_t step) {
  return {header(run_id, step), ControlKind::failure, Role::coupler, Role::terrain, 2.5e-6, 1.5e-6,
          "terrain: particle 1234 left the domain (\"snow\" block)"};
}

// Every field of the table (cosim/wire_fields.hpp), so a field added to the
// IDL and the table is checked through every vendor pair without a line here.
#define COSIM_EXPECT_SAME_FIELD(type, name, init) EXPECT_EQ(a.name, b.name) << #name " differs";
inline void expect_same(const SampleHeader& a, const SampleHeader& b) {
  COSIM_WIRE_FIELDS_SampleHeader(COSIM_EXPECT_SAME_FIELD)
}
#define COSIM_EXPECT_SAME(T)                           \
  inline void expect_same(const T& a, const T& b) {    \
    expect_same(a.header, b.header);                   \
    COSIM_WIRE_FIELDS_##T(COSIM_EXPECT_SAME_FIELD)     \
  }
COSIM_WIRE_TOPICS(COSIM_EXPECT_SAME)
#undef COSIM_EXPECT_SAME
#undef COSIM_EXPECT_SAME_FIELD

}  // namespace test_support
