#pragma once
// What the two solvers of a coupled run hand each other at every exchange, the
// same types on both sides and without any transport: the surface's owner (the
// tyre) offers a SurfaceTopology once and a SurfaceState at each exchange; the
// terrain answers with SurfaceLoads. They carry the fields of the wire's
// SurfaceMesh, SurfaceKinematics and ContactLoads (idl/cosim_topics.idl), the
// only schema, expanded from the table of its fields (cosim/wire_fields.hpp);
// the DDS ports copy them to and from the topics field by field.
// Node and facet numbers are the owner's surface numbering throughout.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cosim/facet_tag.hpp"
#include "cosim/wire_fields.hpp"

namespace cosim {

// The contact surface, offered once: the SurfaceMesh topic's fields but the
// tyre model's node ids (cosim/wire_fields.hpp says what each field is).
struct SurfaceTopology {
  COSIM_WIRE_FIELDS_SurfaceTopology(COSIM_WIRE_DECLARE_FIELD)
  std::size_t node_count() const { return x_m.size(); }
  std::size_t facet_count() const { return facet_tags.size(); }
};

// The part of the surface near the terrain at one exchange: the
// SurfaceKinematics topic's fields, its header as exchange and time.
struct SurfaceState {
  std::uint64_t exchange = 0;
  double time_s = 0.0;
  COSIM_WIRE_FIELDS_SurfaceKinematics(COSIM_WIRE_DECLARE_FIELD)
};

// The terrain's loads on the surface at one exchange, sparse (the nodes and
// the facets that carry any): the ContactLoads topic's fields, its header as
// exchange and time.
struct SurfaceLoads {
  std::uint64_t exchange = 0;
  double time_s = 0.0;
  COSIM_WIRE_FIELDS_ContactLoads(COSIM_WIRE_DECLARE_FIELD)
};

struct SurfaceLoadTotals {
  std::array<double, 3> force_N{0.0, 0.0, 0.0};  // sum over the nodes, in their order
  double contact_area_m2 = 0.0;                 // sum over the facets
};
SurfaceLoadTotals totals(const SurfaceLoads& loads);

// Consistency checks. Throw cosim::Error naming `what` (the sample, e.g.
// "SurfaceKinematics of step 12") and the field: sequence lengths, node and
// facet numbers in range.
void check_surface_topology(const SurfaceTopology& topology, const std::string& what);
// A state from the owner has no friction yet; one that reached the terrain must
// have one coefficient per facet (friction_required).
void check_surface_state(const SurfaceState& state, const SurfaceTopology& topology, const std::string& what,
                         bool friction_required = false);
void check_surface_loads(const SurfaceLoads& loads, const SurfaceTopology& topology, const std::string& what);

}  // namespace cosim
