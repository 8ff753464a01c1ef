#pragma once
// Vendor-neutral mirrors of the wire types in idl/cosim_topics.idl: what the
// solvers and the coupler read and write. One struct per topic, the same
// fields in the same order as the IDL (structure of arrays, SI units in the
// names). Each backend converts these to and from its generated types; the
// Cyclone backend checks at compile time that every struct here has as many
// fields as its IDL counterpart, and tests/transport/test_transport_roundtrip.cpp
// round-trips every field through every vendor pair.
#include <cstdint>
#include <string>
#include <vector>

#include "cosim/facet_tag.hpp"

namespace cosim::transport {

// Facet regions: the project's one facet-tag enum (cosim/facet_tag.hpp).
using FacetTag = cosim::FacetTag;
using cosim::kFacetTagCount;

// Participant roles; `any` addresses everybody.
enum class Role : std::uint8_t { any, tyre, terrain, coupler, monitor };
constexpr int kRoleCount = 5;
const char* role_name(Role role);  // "any", "tyre", "terrain", "coupler", "monitor"

enum class ControlKind : std::uint8_t {
  hello, ready, start, stop, heartbeat, failure,
  checkpoint_request,  // a solver asks the coupler for a stop at a common checkpoint
  checkpoint_at        // the coupler names its exchange (header.step); the solvers echo it
};
constexpr int kControlKindCount = 8;
const char* control_kind_name(ControlKind kind);

// First field of every sample.
struct SampleHeader {
  std::uint64_t run_id = 0;  // random per run (new_run_id()), shared by all its processes
  std::uint64_t step = 0;
  double sim_time_s = 0.0;
};

// The tyre's contact surface; published once, durable for late joiners.
struct SurfaceMesh {
  SampleHeader header;
  std::vector<std::uint32_t> node_ids;     // tyre model node of surface node k
  std::vector<double> x_m, y_m, z_m;       // reference positions per surface node
  std::vector<std::uint32_t> facet_nodes;  // 4 surface-node indices per quad facet
  std::vector<FacetTag> facet_tags;        // one per facet
  std::vector<double> node_mass_kg;        // lumped mass per surface node
};

// Per step: surface nodes near the terrain and friction per nearby facet.
struct SurfaceKinematics {
  SampleHeader header;
  std::vector<std::uint32_t> nodes;           // surface-node indices included
  std::vector<double> x_m, y_m, z_m;          // one per entry of nodes
  std::vector<double> vx_mps, vy_mps, vz_mps;
  std::vector<std::uint32_t> facets;          // surface facet indices
  std::vector<double> friction_coefficient;   // one per entry of facets
};

// Per step: sparse loads on the contacted nodes and facets.
struct ContactLoads {
  SampleHeader header;
  std::vector<std::uint32_t> nodes;
  std::vector<double> fx_N, fy_N, fz_N;
  std::vector<std::uint32_t> facets;
  std::vector<double> normal_force_N;
  std::vector<double> pressure_x_N, pressure_y_N, pressure_z_N;
  std::vector<double> tangential_x_N, tangential_y_N, tangential_z_N;
  std::vector<double> contact_area_m2;
  std::vector<double> pressure_Pa;
  double particle_reach_z_m = 0.0;  // highest point the particles can touch before the next exchange
};

// Per step: the rigid rim.
struct WheelState {
  SampleHeader header;
  double rim_x_m = 0.0;
  double rim_z_m = 0.0;
  double rotation_angle_rad = 0.0;
  double forward_speed_mps = 0.0;
  double spin_rate_radps = 0.0;
  double applied_torque_Nm = 0.0;
  double reaction_moment_y_Nm = 0.0;  // RM2
  double wheel_load_N = 0.0;
  double rim_longitudinal_force_N = 0.0;  // the tyre's force on the rim along x, forward +
};

// Per step: the thesis's force decomposition (F1, F2, F3, F5 and the rest).
struct ForceSummary {
  SampleHeader header;
  double traction_force_N = 0.0;            // F3
  double motion_resistance_N = 0.0;         // F1
  double groove_force_N = 0.0;              // F2
  double rolling_resistance_force_N = 0.0;  // F5
  double drawbar_pull_N = 0.0;
  double net_longitudinal_pressure_force_N = 0.0;
  double sinkage_m = 0.0;
  double contact_area_m2 = 0.0;
};

// Handshake, start/stop, liveness, failures.
struct RunControl {
  SampleHeader header;
  ControlKind kind = ControlKind::hello;
  Role sender = Role::any;
  Role addressee = Role::any;
  double proposed_time_step_s = 0.0;
  double agreed_time_step_s = 0.0;
  std::string reason;
};

// Topic name on the wire (the same for both vendors) of each struct.
template <class T> struct TopicName;
template <> struct TopicName<SurfaceMesh> { static constexpr const char* value = "cosim_SurfaceMesh"; };
template <> struct TopicName<SurfaceKinematics> { static constexpr const char* value = "cosim_SurfaceKinematics"; };
template <> struct TopicName<ContactLoads> { static constexpr const char* value = "cosim_ContactLoads"; };
template <> struct TopicName<WheelState> { static constexpr const char* value = "cosim_WheelState"; };
template <> struct TopicName<ForceSummary> { static constexpr const char* value = "cosim_ForceSummary"; };
template <> struct TopicName<RunControl> { static constexpr const char* value = "cosim_RunControl"; };

// A fresh random, non-zero run id (std::random_device).
std::uint64_t new_run_id();

}  // namespace cosim::transport
