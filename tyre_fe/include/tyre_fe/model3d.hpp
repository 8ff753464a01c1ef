#pragma once
// The 3D tyre model: the revolved mesh with everything the explicit step needs
// precomputed once (element reference data, materials, lumped masses, the
// node -> element map for a deterministic gather, the loaded and contacting
// surfaces).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "tyre_fe/axisym.hpp"
#include "tyre_fe/elements.hpp"
#include "tyre_fe/hex8_batch.hpp"
#include "tyre_fe/materials.hpp"
#include "tyre_fe/mesh.hpp"

namespace tyre_fe {

struct Model3dOptions {
  double time_step_safety = 0.8;       // dt = safety * min(L_e / c_e)
  double mass_scaling_target_dt_s = 0.0;  // > 0: scale element density up to this step
  double bulk_viscosity_linear = 0.06;    // Abaqus/Explicit default b1 (damps volumetric ringing)
};

// Per-element data in arrays (one entry per hex).
struct Model3d {
  Mesh3D mesh;
  TyreMaterials materials;
  std::vector<Hex8Reference> reference;
  std::vector<int> material;                 // region index into materials.solid
  std::vector<Eigen::Vector3d> rebar_direction;  // reference unit direction a0
  std::vector<double> rebar_fraction;        // 0: no rebar
  std::vector<double> rebar_modulus_Pa;
  std::vector<double> element_density;       // after mass scaling [kg/m^3, incl. rebar]
  std::vector<double> element_wave_speed;    // dilatational, with rebar
  std::vector<double> node_mass_kg;
  // The hexahedra in batches for the force loop (hex8_batch.hpp).
  Hex8Batches hex_batches;
  // node -> offsets of its forces in the batched force array (Hex8Batches::force_offset)
  // in CSR form, for a gather that gives the same sums on any thread count.
  std::vector<int> node_hex_begin, node_hex_entries;
  // Facets loaded by the inflation pressure (indices into mesh.facets).
  std::vector<int> pressure_facets;
  // Nodes that may touch the road (outer surface), their reference tributary area
  // projected on the road (a tyre's facets radially, a block's downwards): the
  // footprint, in which groove and sipe walls count nothing.
  std::vector<int> contact_nodes;
  std::vector<double> contact_node_area_m2;
  std::vector<char> is_rim_node;
  double stable_dt_s = 0.0;       // after mass scaling
  double unscaled_dt_s = 0.0;     // before
  double physical_mass_kg = 0.0;
  double added_mass_kg = 0.0;
  int dt_controlling_element = -1;
  // Per region: smallest unscaled element step and mass added by scaling (0 if none).
  std::array<double, kRegionCount> region_min_dt_s{};
  std::array<double, kRegionCount> region_added_mass_kg{};
  Model3dOptions options;
};

// Builds the model; throws cosim::Error for an inverted element (naming it).
Model3d build_model3d(Mesh3D mesh, const TyreMaterials& materials, const CrossSection& section,
                      const Model3dOptions& options);

}  // namespace tyre_fe
