#pragma once
// A Lagrangian axisymmetric finite-element model of snow: the independent
// check of the snow's parameters that the plate-sinkage test needs (thesis
// section 3.2 ran the same test with a Lagrangian mesh: 0.159 m). It uses the
// particles' constitutive update, mdpc_update, at every integration point, so
// that a difference between it and the SPH is a difference of discretisation,
// not of material.
//
// Elements: 4-node quads in the (r, z) half-plane, 2 x 2 Gauss points, with the
// mean-dilatation B-bar treatment of the volumetric rate (Hughes 1980, "Generalization
// of selective integration procedures to anisotropic and nonlinear media", IJNME 15,
// 1413-1418; Simo & Hughes 1998, Computational Inelasticity, sec. 4.4): the
// volumetric rate at each point is replaced by its volume average over the
// element, so that the plastic flow of a pressure-sensitive material does not
// lock and no hourglass control is needed. Updated Lagrangian, rate form:
// the rate of deformation and spin at the current configuration, the Jaumann
// rate for objectivity (as Abaqus/Explicit's solid elements), mdpc_update for
// the increment. Explicit central differences with lumped (row-sum) masses.
//
// Stress components are stored in a 3 x 3 tensor in the basis (r, z, theta):
// (0,0) = sigma_rr, (1,1) = sigma_zz, (2,2) = sigma_thetatheta, (0,1) = sigma_rz.
// Forces and masses are per radian of the revolved body.
//
// The same element in plane strain (Geometry::plane_strain; the strip footing
// of strip_fe.hpp): r reads x, the hoop terms N_a / r are dropped and the
// out-of-plane rate of deformation is zero (Zienkiewicz & Taylor, The Finite
// Element Method, vol. 1, 6th ed., ch. 6: the axisymmetric element is the
// plane one with the weight 2 pi r and the hoop strain u_r / r added). The
// component (2,2) is then sigma_yy, out of plane, and "per radian" reads
// "per metre" of the out-of-plane length.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "snow_sph/mdpc.hpp"

namespace snow_fe::axisym {

// Axisymmetric (r, z) or plane strain (x, z); see the header comment.
enum class Geometry { axisymmetric, plane_strain };

// A structured mesh of (r_lines - 1) x (z_lines - 1) quads. Node (i, j) sits at
// (r_lines[i], z_lines[j]) in the reference state; its index is j * nodes_r + i.
struct Mesh {
  int nodes_r = 0, nodes_z = 0;
  std::vector<double> r_m, z_m;          // current node positions
  std::vector<double> v_r, v_z;          // node velocities (at the half step)
  std::vector<double> mass_kg_per_rad;   // lumped, constant (Lagrangian)
  std::vector<std::uint8_t> hold_r, hold_z;  // 1: that velocity is prescribed (kept as set)
  // Per Gauss point 4 e + g, element e = j (nodes_r - 1) + i.
  std::vector<Eigen::Matrix3d> stress_Pa;
  std::vector<double> eps_vol_pl;
  double density_kg_per_m3 = 0.0;
  Geometry geometry = Geometry::axisymmetric;

  int node(int i, int j) const { return j * nodes_r + i; }
  int elements_r() const { return nodes_r - 1; }
  int elements() const { return (nodes_r - 1) * (nodes_z - 1); }
  int nodes() const { return nodes_r * nodes_z; }
};

// Lines must be strictly increasing, r_lines[0] >= 0, at least two each.
// Throws cosim::Error otherwise. Stresses start at zero, eps_vol_pl at
// params.initial_cap_volumetric_plastic_strain.
Mesh make_mesh(const std::vector<double>& r_lines_m, const std::vector<double>& z_lines_m, double density_kg_per_m3,
               const snow_sph::MdpcParameters& params, Geometry geometry = Geometry::axisymmetric);

// Gauss point positions (reference) of element e, for initial stress fields.
Eigen::Vector2d gauss_point_position(const Mesh& mesh, int element, int point);

struct ElementPassResult {
  double plastic_work_J_per_rad = 0.0;   // sigma : d eps_p over the pass
  double smallest_jacobian_ratio = 1.0;  // min over points of det J / (element area / 4); <= 0: inverted
};

// One pass over the elements at the current positions: advances every Gauss
// point's stress by dt with the current velocities (rate of deformation with
// B-bar, Jaumann rotation, mdpc_update) and writes the internal nodal forces
// (per radian, the force the snow exerts on the node: -integral B^T sigma r dA)
// into f_r, f_z (resized). With dt = 0 the stresses are left as they are.
ElementPassResult element_pass(Mesh& mesh, const snow_sph::MdpcParameters& params, double dt,
                               std::vector<double>& f_r, std::vector<double>& f_z);

// Accelerations of the nodes under forces f (per radian) and gravity g along
// -z; a held velocity component gets zero acceleration.
void nodal_accelerations(const Mesh& mesh, const std::vector<double>& f_r, const std::vector<double>& f_z,
                         double gravity_m_per_s2, std::vector<double>& a_r, std::vector<double>& a_z);

// Central-difference update of the nodes: v += dt_v a (dt_v the mean of the
// last and this step), then x += dt v. damping_per_s > 0 adds mass-proportional
// damping for quasi-static solutions (dynamic relaxation: v = (v + dt_v a) /
// (1 + c dt_v)); transient runs pass 0.
void advance_nodes(Mesh& mesh, const std::vector<double>& a_r, const std::vector<double>& a_z, double dt_v,
                   double dt, double damping_per_s = 0.0);

// Stable time step of the current mesh for a material whose elastic P-wave
// speed is wave_speed: fraction x min over elements of sqrt(2) A / (longest
// diagonal) / wave_speed (a square of side h gives h / c).
double stable_time_step(const Mesh& mesh, double wave_speed_m_per_s, double fraction);

// Kinetic energy per radian of the nodes.
double kinetic_energy_J_per_rad(const Mesh& mesh);

// Elastic strain energy per radian stored in the stresses (isotropic Hooke:
// p^2 / 2K + q^2 / 6G per unit current volume), for energy balances.
double elastic_energy_J_per_rad(const Mesh& mesh, const snow_sph::MdpcParameters& params);

}  // namespace snow_fe::axisym
