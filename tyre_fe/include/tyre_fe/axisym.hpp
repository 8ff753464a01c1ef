#pragma once
// Quasi-static axisymmetric solver for a CrossSection: tyre inflation and the Lame
// verification test. Explicit dynamic relaxation (Underwood 1983, "Dynamic
// relaxation", in Computational Methods for Transient Analysis, ch. 5): central
// difference in time, lumped mass per radian, kinetic damping (velocities zeroed at
// each peak of the kinetic energy; measured faster here than critical viscous
// damping, see axisym.cpp), pressure ramped smoothly then held. Time step: 0.8 x the
// smallest element bound quad4axi_stable_time_step_s (elements.hpp). Elements: the
// one-point Quad4Axi with twist (CGAX4R-type, elements.hpp): three dofs per node,
// u_r, u_y and the twist angle phi about the axis, so that the r-theta and y-theta
// shear stresses of angled rebar (belts at +-66.7 deg) do work and the inflated state
// is an equilibrium of the revolved 3D model too (Abaqus uses CGAX elements before
// *SYMMETRIC MODEL GENERATION for this reason). Serial, so results do not depend on
// the thread count.
//
// Twist dof: phi itself [rad], lumped rotational inertia m_i R_i^2 per radian (R_i
// the reference node radius), conjugate generalised force the moment about the axis
// M_i [N m per radian]. In the residual and kinetic-energy checks it enters as the hoop
// displacement R_i phi_i with force M_i / R_i and mass m_i, so all dofs have the units
// of force and length. Nodes on the axis (R_i = 0) have their twist held.
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "tyre_fe/materials.hpp"
#include "tyre_fe/mesh.hpp"

namespace tyre_fe {

// Materials per region (index = int(Region)).
struct TyreMaterials {
  std::array<SolidMaterial, kRegionCount> solid;
  // Smeared rebar per region; area_m2 == 0: none. In a quad the reference bar
  // direction in (r, y, theta) is a0 = cos(angle) (t_r, t_y, 0) + sin(angle) (0, 0, 1),
  // t = section.quad_layer_tangent, volume fraction area / (spacing * layer thickness).
  // The bar mass (density * volume fraction per unit volume) is added to the host.
  std::array<RebarLayer, kRegionCount> rebar;
  double hourglass_coefficient = 0.05;  // see hex8_internal_forces / quad4axi_internal_forces
};

struct AxisymLoadCase {
  // Inflation pressure on section.inner_liner_edges: a follower load on the deformed
  // edge, traction -p n with n the element's outward normal (it pushes the liner away
  // from the cavity), consistent nodal forces of the axisymmetric measure r ds.
  double pressure_Pa = 0.0;
  // Nodes with all three dofs (r, y, twist) held at their reference position (the rim
  // holds the bead against turning as well); nullopt: section.rim_nodes.
  std::optional<std::vector<int>> fixed_nodes;
  std::vector<int> fixed_y_nodes;      // only y held (e.g. plane-strain ends of a cylinder)
  std::vector<int> fixed_twist_nodes;  // only the twist held (phi = 0)
  // Duration of the smooth (1 - cos) pressure ramp; 0: twice the longest shear-wave
  // transit time across the section (extent / slowest shear wave speed).
  double ramp_time_s = 0.0;
  long max_steps = 2000000;
  // Converged when, after the ramp, |R| <= tolerance |F_ext| (Euclidean norms of the
  // residual over free dofs, twist moments as hoop forces M_i / R_i, and of the
  // external load) and the kinetic energy (twist included) is
  // <= tolerance * |F_ext . u| / 2 (the external work).
  double tolerance = 1e-6;
  // Quasi-static only: elements whose stable step is below this are given fictitious
  // extra density so that it reaches this value (the equilibrium does not depend on
  // the masses). 0: physical masses.
  double mass_scaling_time_step_s = 0.0;
};

struct AxisymResult {
  std::vector<Eigen::Vector2d> nodes;  // deformed (r, y) [m]
  // Per node, the twist angle phi about the axis [rad] (right-handed about +y, the
  // direction of increasing theta): the node at angle theta of the revolved model goes
  // to (r sin(theta + phi), y, r cos(theta + phi)).
  std::vector<double> twist_rad;
  long steps = 0;
  double residual_ratio = 0.0;         // |R| / |F_ext| at the end
  double kinetic_energy_J_per_rad = 0.0;
  double strain_energy_J_per_rad = 0.0;     // solid + rebar, without hourglass
  double hourglass_energy_J_per_rad = 0.0;  // should stay a small fraction of the above
  double time_step_s = 0.0;  // 0.8 x the smallest element bound quad4axi_stable_time_step_s
  bool converged = false;
  // Per quad, at the centroid: Cauchy stress in (r, y, theta) of rubber plus smeared
  // rebar (with twist the r-theta and y-theta shear components as well), and the bar
  // log strain ln |F a0| (0 without rebar).
  std::vector<Eigen::Matrix3d> quad_stress_Pa;
  std::vector<double> quad_rebar_log_strain;
};

// Throws cosim::Error on invalid input (sizes, node indices, materials, element
// geometry) and if the iteration diverges (non-finite residual, inverted element).
// Not converging within max_steps is reported by converged = false, not thrown.
// progress(step, residual_ratio) is called every 1000 steps if set.
AxisymResult solve_axisym(const CrossSection& section, const TyreMaterials& materials,
                          const AxisymLoadCase& load,
                          const std::function<void(long step, double residual_ratio)>& progress = {});

}  // namespace tyre_fe
