#pragma once
// Vendor-neutral mirrors of the wire types in idl/cosim_topics.idl: what the
// solvers and the coupler read and write. One struct per topic, the same
// fields in the same order as the IDL (structure of arrays, SI units in the
// names), expanded from one table (cosim/wire_fields.hpp) that
// tests/common/test_wire_fields.cpp checks against the IDL. Each backend converts
// these to and from its generated types field by field from the same table;
// the Cyclone backend also checks at compile time that every struct here has
// as many fields as its IDL counterpart, and tests/transport/test_transport_roundtrip.cpp
// round-trips every field through every vendor pair.
#include <cstdint>
#include <string>
#include <vector>

#include "cosim/facet_tag.hpp"
#include "cosim/wire_fields.hpp"

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

// One struct per topic, its fields expanded from the table of
// idl/cosim_topics.idl's fields (cosim/wire_fields.hpp): the same names, types
// and order as the IDL, every topic led by its SampleHeader.
struct SampleHeader {
  COSIM_WIRE_FIELDS_SampleHeader(COSIM_WIRE_DECLARE_FIELD)
};

// The tyre's contact surface; published once, durable for late joiners.
struct SurfaceMesh {
  SampleHeader header;
  COSIM_WIRE_FIELDS_SurfaceMesh(COSIM_WIRE_DECLARE_FIELD)
};

// Per step: surface nodes near the terrain and friction per nearby facet.
struct SurfaceKinematics {
  SampleHeader header;
  COSIM_WIRE_FIELDS_SurfaceKinematics(COSIM_WIRE_DECLARE_FIELD)
};

// Per step: sparse loads on the contacted nodes and facets.
struct ContactLoads {
  SampleHeader header;
  COSIM_WIRE_FIELDS_ContactLoads(COSIM_WIRE_DECLARE_FIELD)
};

// Per step: the rigid rim.
struct WheelState {
  SampleHeader header;
  COSIM_WIRE_FIELDS_WheelState(COSIM_WIRE_DECLARE_FIELD)
};

// Per step: the thesis's force decomposition (F1, F2, F3, F5 and the rest).
struct ForceSummary {
  SampleHeader header;
  COSIM_WIRE_FIELDS_ForceSummary(COSIM_WIRE_DECLARE_FIELD)
};

// Handshake, start/stop, liveness, failures.
struct RunControl {
  SampleHeader header;
  COSIM_WIRE_FIELDS_RunControl(COSIM_WIRE_DECLARE_FIELD)
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
