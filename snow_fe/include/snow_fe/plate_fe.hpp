#pragma once
// The plate-sinkage test (thesis section 3.2) on a Lagrangian axisymmetric
// finite-element mesh of the same snow (axisym_fe.hpp): a rigid disc on the
// axis, loaded (or pushed at a prescribed speed) into a cylindrical slab whose
// side and bottom are rollers, as the thesis's Lagrangian and CEL models
// ("all other sides and bottom have been constrained normal to the surface").
//
// The slab: the SPH scene's box is 0.6 x 0.6 m (a quarter of it simulated); the
// axisymmetric slab has the same plan area, radius 0.6 / sqrt(pi) = 0.339 m.
//
// Contact between the plate's bottom face and the slab's top nodes under it
// (current radius <= plate radius) is kinematic (the constraint enforced exactly
// at each step, momentum conserved between the plate and the nodes, as
// Abaqus/Explicit's kinematic contact: Abaqus Analysis User's Guide, "Contact
// constraint enforcement methods in Abaqus/Explicit"), so no contact stiffness
// or damping enters; Coulomb friction on the face limits each node's radial
// impulse to mu times its normal impulse. No damping and no bulk viscosity:
// plasticity is the only dissipation.
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/result_references.hpp"
#include "cosim/scene_io.hpp"
#include "snow_sph/mdpc.hpp"

namespace snow_fe {

struct PlateFeSetup {
  std::string name = "plate_sinkage_fe";
  snow_sph::MdpcParameters snow;
  double density_kg_per_m3 = 0.0;
  double slab_radius_m = 0.0, slab_depth_m = 0.0;
  double element_size_m = 0.0;  // target; the plate's edge is always a node line
  double plate_radius_m = 0.0, plate_mass_kg = 0.0, friction_coefficient = 0.0;
  double gravity_m_per_s2 = 9.81;  // magnitude, acting along -z
  // Drive: a downward force ramped (smootherstep, as the SPH bodies) then held,
  // or, when prescribed_speed_m_per_s > 0, a downward speed from t = 0.
  double applied_force_N = 0.0, load_ramp_time_s = 0.0;
  double prescribed_speed_m_per_s = 0.0;
  double end_time_s = 0.0;
  double output_interval_s = 5e-4;
  double time_step_fraction = 0.4;  // of sqrt(2) A / diagonal / c, see stable_time_step
  bool geostatic_initial_state = true;
  cosim::ResultReferences references;  // the scene's: summary "comparison"
};

// From an SPH plate-sinkage scene: its first block's snow, its box, its first
// rigid body, gravity, end time, output interval and references. The element size is the
// particle spacing unless element_size_m > 0. Throws cosim::Error naming the
// field when the scene is not a plate-sinkage scene.
PlateFeSetup plate_fe_setup_from_scene(const cosim::LoadedScene& scene, double element_size_m = 0.0);

// Runs the test; writes <out>/plate.csv (time series), <out>/mesh_final.csv
// (element outlines of the deformed mesh), <out>/summary.json and PNG plots;
// returns the summary. A run whose mesh inverts stops there with status
// "mesh_inverted" and keeps everything written up to that step.
nlohmann::json run_plate_fe(const PlateFeSetup& setup, const std::string& out_folder, bool quiet);

}  // namespace snow_fe
