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

inline SurfaceMesh mesh_sample(std::uint64_t run_id, std::size_t n) {
  SurfaceMesh m;
  m.header = header(run_id, 0);
  m.node_ids = ids(n, 100000);
  m.x_m = doubles(n, 1);
  m.y_m = doubles(n, 2);
  m.z_m = doubles(n, 3);
  m.facet_nodes = ids(4 * n, 5);
  for (std::size_t i = 0; i < n; ++i) m.facet_tags.push_back(static_cast<FacetTag>(i % kFacetTagCount));
  m.node_mass_kg = doubles(n, 6);
  return m;
}
inline SurfaceKinematics kinematics_sample(std::uint64_t run_id, std::uint64_t step, std::size_t n) {
  SurfaceKinematics k;
  k.header = header(run_id, step);
  k.nodes = ids(n, 11);
  k.x_m = doubles(n, 1, step);
  k.y_m = doubles(n, 2, step);
  k.z_m = doubles(n, 3, step);
  k.vx_mps = doubles(n, 4, step);
  k.vy_mps = doubles(n, 5, step);
  k.vz_mps = doubles(n, 6, step);
  k.facets = ids(n / 2 + 1, 13);
  k.friction_coefficient = doubles(n / 2 + 1, 7, step);
  return k;
}
inline ContactLoads loads_sample(std::uint64_t run_id, std::uint64_t step, std::size_t n) {
  ContactLoads l;
  l.header = header(run_id, step);
  l.nodes = ids(n, 17);
  l.fx_N = doubles(n, 11, step);
  l.fy_N = doubles(n, 12, step);
  l.fz_N = doubles(n, 13, step);
  l.facets = ids(n + 3, 19);
  l.normal_force_N = doubles(n + 3, 14, step);
  l.pressure_x_N = doubles(n + 3, 20, step);
  l.pressure_y_N = doubles(n + 3, 21, step);
  l.pressure_z_N = doubles(n + 3, 22, step);
  l.tangential_x_N = doubles(n + 3, 15, step);
  l.tangential_y_N = doubles(n + 3, 16, step);
  l.tangential_z_N = doubles(n + 3, 17, step);
  l.contact_area_m2 = doubles(n + 3, 18, step);
  l.pressure_Pa = doubles(n + 3, 19, step);
  return l;
}
inline WheelState wheel_sample(std::uint64_t run_id, std::uint64_t step) {
  return {header(run_id, step), 0.125, 0.3125, 1.5, 2.7778, 9.25, 310.5, -42.75, 4000.5, -187.25};
}
inline ForceSummary forces_sample(std::uint64_t run_id, std::uint64_t step) {
  return {header(run_id, step), 812.5, 95.25, 33.125, 41.5, 717.25, -12.5, 0.0625, 0.0185};
}
inline RunControl control_sample(std::uint64_t run_id, std::uint64_t step) {
  return {header(run_id, step), ControlKind::failure, Role::coupler, Role::terrain, 2.5e-6, 1.5e-6,
          "terrain: particle 1234 left the domain (\"snow\" block)"};
}

inline void expect_same(const SampleHeader& a, const SampleHeader& b) {
  EXPECT_EQ(a.run_id, b.run_id);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.sim_time_s, b.sim_time_s);
}
inline void expect_same(const SurfaceMesh& a, const SurfaceMesh& b) {
  expect_same(a.header, b.header);
  EXPECT_EQ(a.node_ids, b.node_ids);
  EXPECT_EQ(a.x_m, b.x_m);
  EXPECT_EQ(a.y_m, b.y_m);
  EXPECT_EQ(a.z_m, b.z_m);
  EXPECT_EQ(a.facet_nodes, b.facet_nodes);
  EXPECT_TRUE(a.facet_tags == b.facet_tags) << "facet_tags differ";
  EXPECT_EQ(a.node_mass_kg, b.node_mass_kg);
}
inline void expect_same(const SurfaceKinematics& a, const SurfaceKinematics& b) {
  expect_same(a.header, b.header);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.x_m, b.x_m);
  EXPECT_EQ(a.y_m, b.y_m);
  EXPECT_EQ(a.z_m, b.z_m);
  EXPECT_EQ(a.vx_mps, b.vx_mps);
  EXPECT_EQ(a.vy_mps, b.vy_mps);
  EXPECT_EQ(a.vz_mps, b.vz_mps);
  EXPECT_EQ(a.facets, b.facets);
  EXPECT_EQ(a.friction_coefficient, b.friction_coefficient);
}
inline void expect_same(const ContactLoads& a, const ContactLoads& b) {
  expect_same(a.header, b.header);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.fx_N, b.fx_N);
  EXPECT_EQ(a.fy_N, b.fy_N);
  EXPECT_EQ(a.fz_N, b.fz_N);
  EXPECT_EQ(a.facets, b.facets);
  EXPECT_EQ(a.normal_force_N, b.normal_force_N);
  EXPECT_EQ(a.pressure_x_N, b.pressure_x_N);
  EXPECT_EQ(a.pressure_y_N, b.pressure_y_N);
  EXPECT_EQ(a.pressure_z_N, b.pressure_z_N);
  EXPECT_EQ(a.tangential_x_N, b.tangential_x_N);
  EXPECT_EQ(a.tangential_y_N, b.tangential_y_N);
  EXPECT_EQ(a.tangential_z_N, b.tangential_z_N);
  EXPECT_EQ(a.contact_area_m2, b.contact_area_m2);
  EXPECT_EQ(a.pressure_Pa, b.pressure_Pa);
}
inline void expect_same(const WheelState& a, const WheelState& b) {
  expect_same(a.header, b.header);
  EXPECT_EQ(a.rim_x_m, b.rim_x_m);
  EXPECT_EQ(a.rim_z_m, b.rim_z_m);
  EXPECT_EQ(a.rotation_angle_rad, b.rotation_angle_rad);
  EXPECT_EQ(a.forward_speed_mps, b.forward_speed_mps);
  EXPECT_EQ(a.spin_rate_radps, b.spin_rate_radps);
  EXPECT_EQ(a.applied_torque_Nm, b.applied_torque_Nm);
  EXPECT_EQ(a.reaction_moment_y_Nm, b.reaction_moment_y_Nm);
  EXPECT_EQ(a.wheel_load_N, b.wheel_load_N);
  EXPECT_EQ(a.rim_longitudinal_force_N, b.rim_longitudinal_force_N);
}
inline void expect_same(const ForceSummary& a, const ForceSummary& b) {
  expect_same(a.header, b.header);
  EXPECT_EQ(a.traction_force_N, b.traction_force_N);
  EXPECT_EQ(a.motion_resistance_N, b.motion_resistance_N);
  EXPECT_EQ(a.groove_force_N, b.groove_force_N);
  EXPECT_EQ(a.rolling_resistance_force_N, b.rolling_resistance_force_N);
  EXPECT_EQ(a.drawbar_pull_N, b.drawbar_pull_N);
  EXPECT_EQ(a.net_longitudinal_pressure_force_N, b.net_longitudinal_pressure_force_N);
  EXPECT_EQ(a.sinkage_m, b.sinkage_m);
  EXPECT_EQ(a.contact_area_m2, b.contact_area_m2);
}
inline void expect_same(const RunControl& a, const RunControl& b) {
  expect_same(a.header, b.header);
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.sender, b.sender);
  EXPECT_EQ(a.addressee, b.addressee);
  EXPECT_EQ(a.proposed_time_step_s, b.proposed_time_step_s);
  EXPECT_EQ(a.agreed_time_step_s, b.agreed_time_step_s);
  EXPECT_EQ(a.reason, b.reason);
}

}  // namespace test_support
