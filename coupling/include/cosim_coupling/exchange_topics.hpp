#pragma once
// The exchange types of the solvers (cosim/surface_exchange.hpp) to and from
// their wire topics (idl/cosim_topics.idl): one field-by-field copy each way,
// used by both solvers' DDS ports.
#include <cstdint>

#include "cosim/surface_exchange.hpp"
#include "cosim_transport/topics.hpp"

namespace cosim::coupling {

void to_topic(const SurfaceState& state, std::uint64_t run_id, transport::SurfaceKinematics& out);
void from_topic(const transport::SurfaceKinematics& sample, SurfaceState& out);
void to_topic(const SurfaceLoads& loads, std::uint64_t run_id, transport::ContactLoads& out);
void from_topic(const transport::ContactLoads& sample, SurfaceLoads& out);
// The mesh's topology; its node ids (the tyre's own numbering) and header are
// the caller's.
void to_topic(const SurfaceTopology& topology, transport::SurfaceMesh& out);
void from_topic(const transport::SurfaceMesh& sample, SurfaceTopology& out);

}  // namespace cosim::coupling
