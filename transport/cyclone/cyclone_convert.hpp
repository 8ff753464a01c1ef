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

// Per topic of cosim/wire_fields.hpp: its two conversions, and its generated
// C struct and topic descriptor.
template <class T> struct WireTypes;
#define COSIM_CYCLONE_WIRE_TYPES(T)                                                                  \
  void view(const T& s, cosim_wire_##T& w, Scratch& scratch);                                        \
  void from_wire(const cosim_wire_##T& w, T& s);                                                     \
  template <> struct WireTypes<T> {                                                                  \
    using Wire = cosim_wire_##T;                                                                     \
    static const dds_topic_descriptor_t* descriptor() { return &cosim_wire_##T##_desc; }             \
  };
COSIM_WIRE_TOPICS(COSIM_CYCLONE_WIRE_TYPES)
#undef COSIM_CYCLONE_WIRE_TYPES

}  // namespace cosim::transport::cyclone
