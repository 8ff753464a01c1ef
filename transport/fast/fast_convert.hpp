#pragma once
// Conversions between the neutral topic structs and fastddsgen's classes of
// idl/cosim_topics.idl (namespace cosim_wire). to_wire copies (the wire
// object's capacity is reused from step to step); from_wire moves the
// sequences out of the wire object.
#include "cosim_topics.h"
#include "cosim_topicsPubSubTypes.h"
#include "cosim_transport/topics.hpp"

namespace cosim::transport::fast {

void to_wire(const SurfaceMesh& s, cosim_wire::SurfaceMesh& w);
void to_wire(const SurfaceKinematics& s, cosim_wire::SurfaceKinematics& w);
void to_wire(const ContactLoads& s, cosim_wire::ContactLoads& w);
void to_wire(const WheelState& s, cosim_wire::WheelState& w);
void to_wire(const ForceSummary& s, cosim_wire::ForceSummary& w);
void to_wire(const RunControl& s, cosim_wire::RunControl& w);

void from_wire(cosim_wire::SurfaceMesh& w, SurfaceMesh& s);
void from_wire(cosim_wire::SurfaceKinematics& w, SurfaceKinematics& s);
void from_wire(cosim_wire::ContactLoads& w, ContactLoads& s);
void from_wire(cosim_wire::WheelState& w, WheelState& s);
void from_wire(cosim_wire::ForceSummary& w, ForceSummary& s);
void from_wire(cosim_wire::RunControl& w, RunControl& s);

// Generated wire class and its TopicDataType per neutral struct.
template <class T> struct WireTypes;
template <> struct WireTypes<SurfaceMesh> {
  using Wire = cosim_wire::SurfaceMesh;
  using PubSub = cosim_wire::SurfaceMeshPubSubType;
};
template <> struct WireTypes<SurfaceKinematics> {
  using Wire = cosim_wire::SurfaceKinematics;
  using PubSub = cosim_wire::SurfaceKinematicsPubSubType;
};
template <> struct WireTypes<ContactLoads> {
  using Wire = cosim_wire::ContactLoads;
  using PubSub = cosim_wire::ContactLoadsPubSubType;
};
template <> struct WireTypes<WheelState> {
  using Wire = cosim_wire::WheelState;
  using PubSub = cosim_wire::WheelStatePubSubType;
};
template <> struct WireTypes<ForceSummary> {
  using Wire = cosim_wire::ForceSummary;
  using PubSub = cosim_wire::ForceSummaryPubSubType;
};
template <> struct WireTypes<RunControl> {
  using Wire = cosim_wire::RunControl;
  using PubSub = cosim_wire::RunControlPubSubType;
};

}  // namespace cosim::transport::fast
