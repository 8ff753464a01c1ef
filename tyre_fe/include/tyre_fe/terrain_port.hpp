#pragma once
// The tyre's side of a coupling with a terrain solver, without any transport:
// the contact surface the tyre offers (nodes, quad facets, tags), the loads the
// terrain returns, and the port through which the step loop exchanges them.
// tyre_fe's library never knows what is behind the port (DDS in the
// coupled executable, a test double in tests).
//
// Timing (explicit central difference, Belytschko et al. 2000 box 6.1): at the
// start of coupled step n the tyre sends its surface at t_n (positions x^n,
// velocities v^{n-1/2}), then computes its element forces while the terrain
// works, then receives the contact loads of t_n and adds them to the nodal
// forces of the same step. Both solvers advance with one common step.
#include <cstdint>
#include <string>
#include <vector>

#include "tyre_fe/model3d.hpp"

namespace tyre_fe {

struct State3d;

// The outer surface that can touch a terrain: every tagged facet except the
// inner liner and the rim faces. Surface node k is model node node_ids[k];
// facet f has surface nodes facet_nodes[4f..4f+3] (outward right-hand normal).
struct ContactSurfaceDef {
  std::vector<int> node_ids;
  std::vector<std::uint32_t> facet_nodes;
  std::vector<SurfaceTag> facet_tags;
  std::vector<int> mesh_facets;  // surface facet f is mesh.facets[mesh_facets[f]]
  std::vector<double> node_mass_kg;  // lumped mass of surface node k (empty: not known)
  std::size_t facet_count() const { return facet_tags.size(); }
};
ContactSurfaceDef make_contact_surface(const Mesh3D& mesh);
// With the lumped masses of the model's nodes.
ContactSurfaceDef make_contact_surface(const Model3d& model);

// Forces of the terrain on surface nodes (sparse, surface-node indices).
struct TerrainLoads {
  std::vector<std::uint32_t> surface_nodes;
  std::vector<double> fx_N, fy_N, fz_N;
  double total_x_N = 0.0, total_y_N = 0.0, total_z_N = 0.0;
  double contact_area_m2 = 0.0;  // as the terrain counts it
  // Contact pressure of the contacted facets (surface-facet indices), for the
  // tyre's own outputs; the forces above are what the step uses.
  std::vector<std::uint32_t> facets;
  std::vector<double> facet_pressure_Pa;
};

class TerrainPort {
 public:
  virtual ~TerrainPort() = default;
  // Once, before the first coupled step: offers the surface and this solver's
  // stable step; returns the common step every participant will use.
  virtual double connect(const ContactSurfaceDef& surface, double proposed_dt_s) = 0;
  // Coupled step `exchange` (0, 1, ...) at state s: the surface kinematics and the rim.
  virtual void send(std::uint64_t exchange, const State3d& s, const Model3d& model) = 0;
  // The loads of the same step; throws cosim::Error if the terrain is gone.
  virtual void receive(std::uint64_t exchange, TerrainLoads& loads) = 0;
  // End of the run: normal stop (failed = false) or failure with a reason.
  virtual void finish(bool failed, const std::string& reason) = 0;
};

}  // namespace tyre_fe
