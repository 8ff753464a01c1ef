#pragma once
// Conversions between the neutral topic structs and the C structs Cyclone's
// idlc generates from idl/cosim_topics.idl. Writing needs no copy: view()
// points the C sequences at the neutral vectors (the view must not outlive
// them or the scratch buffers). Reading copies out of the loaned C sample.
#include <cstddef>
#include <deque>
#include <vector>

#include "cosim_topics.h"
#include "cosim_transport/topics.hpp"

namespace cosim::transport::cyclone {

// Buffers for sequences whose element type differs on the wire (enums): one
// per such field of the sample being viewed, kept from sample to sample.
struct Scratch {
  std::deque<std::vector<cosim_wire_FacetTag>> facet_tags;
  std::size_t facet_tags_used = 0;  // view() starts each sample at 0
  std::vector<cosim_wire_FacetTag>& next_facet_tags() {
    if (facet_tags_used == facet_tags.size()) facet_tags.emplace_back();
    return facet_tags[facet_tags_used++];
  }
};

void view(const SurfaceMesh& s, cosim_wire_SurfaceMesh& w, Scratch& scratch);
void view(const SurfaceKinematics& s, cosim_wire_SurfaceKinematics& w, Scratch& scratch);
void view(const ContactLoads& s, cosim_wire_ContactLoads& w, Scratch& scratch);
void view(const WheelState& s, cosim_wire_WheelState& w, Scratch& scratch);
void view(const ForceSummary& s, cosim_wire_ForceSummary& w, Scratch& scratch);
void view(const RunControl& s, cosim_wire_RunControl& w, Scratch& scratch);

void from_wire(const cosim_wire_SurfaceMesh& w, SurfaceMesh& s);
void from_wire(const cosim_wire_SurfaceKinematics& w, SurfaceKinematics& s);
void from_wire(const cosim_wire_ContactLoads& w, ContactLoads& s);
void from_wire(const cosim_wire_WheelState& w, WheelState& s);
void from_wire(const cosim_wire_ForceSummary& w, ForceSummary& s);
void from_wire(const cosim_wire_RunControl& w, RunControl& s);

// Generated C struct and topic descriptor per neutral struct.
template <class T> struct WireTypes;
template <> struct WireTypes<SurfaceMesh> {
  using Wire = cosim_wire_SurfaceMesh;
  static const dds_topic_descriptor_t* descriptor() { return &cosim_wire_SurfaceMesh_desc; }
};
template <> struct WireTypes<SurfaceKinematics> {
  using Wire = cosim_wire_SurfaceKinematics;
  static const dds_topic_descriptor_t* descriptor() { return &cosim_wire_SurfaceKinematics_desc; }
};
template <> struct WireTypes<ContactLoads> {
  using Wire = cosim_wire_ContactLoads;
  static const dds_topic_descriptor_t* descriptor() { return &cosim_wire_ContactLoads_desc; }
};
template <> struct WireTypes<WheelState> {
  using Wire = cosim_wire_WheelState;
  static const dds_topic_descriptor_t* descriptor() { return &cosim_wire_WheelState_desc; }
};
template <> struct WireTypes<ForceSummary> {
  using Wire = cosim_wire_ForceSummary;
  static const dds_topic_descriptor_t* descriptor() { return &cosim_wire_ForceSummary_desc; }
};
template <> struct WireTypes<RunControl> {
  using Wire = cosim_wire_RunControl;
  static const dds_topic_descriptor_t* descriptor() { return &cosim_wire_RunControl_desc; }
};

}  // namespace cosim::transport::cyclone
