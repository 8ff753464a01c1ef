#pragma once
// Conversions between the neutral topic structs and fastddsgen's classes of
// idl/cosim_topics.idl (namespace cosim_wire). to_wire copies (the wire
// object's capacity is reused from step to step); from_wire moves the
// sequences out of the wire object.
#include "cosim_topics.h"
#include "cosim_topicsPubSubTypes.h"
#include "cosim_transport/topics.hpp"

namespace cosim::transport::fast {

// Per topic of cosim/wire_fields.hpp: its two conversions, and its generated
// wire class and TopicDataType.
template <class T> struct WireTypes;
#define COSIM_FAST_WIRE_TYPES(T)                       \
  void to_wire(const T& s, cosim_wire::T& w);          \
  void from_wire(cosim_wire::T& w, T& s);              \
  template <> struct WireTypes<T> {                    \
    using Wire = cosim_wire::T;                        \
    using PubSub = cosim_wire::T##PubSubType;          \
  };
COSIM_WIRE_TOPICS(COSIM_FAST_WIRE_TYPES)
#undef COSIM_FAST_WIRE_TYPES

}  // namespace cosim::transport::fast
