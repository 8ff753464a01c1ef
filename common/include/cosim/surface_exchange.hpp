#pragma once
// What the two solvers of a coupled run hand each other at every exchange, the
// same types on both sides and without any transport: the surface's owner (the
// tyre) offers a SurfaceTopology once and a SurfaceState at each exchange; the
// terrain answers with SurfaceLoads. They carry the fields of the wire's
// SurfaceMesh, SurfaceKinematics and ContactLoads (idl/cosim_topics.idl), the
// only schema, and the DDS ports copy them to and from it field by field.
// Node and facet numbers are the owner's surface numbering throughout.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cosim/facet_tag.hpp"

namespace cosim {

// The contact surface, offered once: quad facets of four surface nodes whose
// right-hand normal (x2 - x0) x (x3 - x1) points out of the owner's body.
struct SurfaceTopology {
  std::vector<double> x_m, y_m, z_m;        // each surface node where the coupled run starts
  std::vector<std::uint32_t> facet_nodes;   // 4 surface nodes per facet
  std::vector<FacetTag> facet_tags;         // one per facet
  std::vector<double> node_mass_kg;         // lumped mass per surface node (empty: not known)
  std::size_t node_count() const { return x_m.size(); }
  std::size_t facet_count() const { return facet_tags.size(); }
};

// The part of the surface near the terrain at one exchange.
struct SurfaceState {
  std::uint64_t exchange = 0;
  double time_s = 0.0;
  std::vector<std::uint32_t> nodes;            // surface nodes included
  std::vector<double> x_m, y_m, z_m;           // one per entry of nodes
  std::vector<double> vx_mps, vy_mps, vz_mps;
  std::vector<std::uint32_t> facets;           // facets included (all their nodes are)
  std::vector<double> friction_coefficient;    // one per facet, decided by the coupler; empty from the owner
};

// The terrain's loads on the surface at one exchange, sparse: the nodes and the
// facets that carry any.
struct SurfaceLoads {
  std::uint64_t exchange = 0;
  double time_s = 0.0;
  std::vector<std::uint32_t> nodes;
  std::vector<double> fx_N, fy_N, fz_N;        // force on the surface node, global frame
  std::vector<std::uint32_t> facets;
  std::vector<double> normal_force_N;          // along the facet normal, compressive > 0
  // The pressure (non-friction) part of the force on the facet, global frame:
  // along each contact's own direction (at an edge, from the closest point to the particle).
  std::vector<double> pressure_x_N, pressure_y_N, pressure_z_N;
  std::vector<double> tangential_x_N, tangential_y_N, tangential_z_N;
  std::vector<double> contact_area_m2;
  std::vector<double> pressure_Pa;
  // The highest point the terrain's particles can touch before the next
  // exchange; the owner sends every facet with a node below it at that
  // exchange. Lowest double: nothing to touch.
  double particle_reach_z_m = -std::numeric_limits<double>::max();
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
