#pragma once
// Element kernels: 8-node hexahedron and 4-node axisymmetric quadrilateral, both
// total Lagrangian with one-point (centroid) integration and Flanagan-Belytschko
// hourglass stiffness (Flanagan & Belytschko 1981, IJNME 17:679-706; Belytschko,
// Liu & Moran 2000, section 8.7). One-point integration does not lock for nearly
// incompressible rubber; the hourglass base vectors gamma are built from the
// reference coordinates so that they annihilate every field linear in X, which
// makes the total-form restoring hourglass force on node i,
// -k sum_a gamma_ai (sum_j gamma_aj x_j), zero for any rigid motion and any
// homogeneous deformation (patch test) and objective under finite rotation.
#include <array>

#include <Eigen/Core>

namespace tyre_fe {

// Reference data of a hexahedron, computed once from its reference node positions.
// Node order: 0-3 the bottom face counter-clockwise seen from above (+zeta), 4-7
// above them (Abaqus C3D8R / VTK_HEXAHEDRON order).
struct Hex8Reference {
  double dNdX[8][3];   // shape-function gradients at the centroid (B0)
  double gamma[4][8];  // Flanagan-Belytschko hourglass base vectors
  double volume_m3;
  // V / A_max of the largest face. Note: for a one-point element with lumped mass,
  // L / c_dilatational is NOT a safe step for nearly incompressible material (the
  // uniform-dilatation mode of a cube gives dt_crit = L / (sqrt(3) c)); use
  // hex8_stable_time_step_s for the step.
  double characteristic_length_m;
  double gradient_sq_sum_per_m2;      // sum_i |dN_i/dX|^2 (hourglass stiffness scale)
  double gradient_gram_max_per_m2;    // largest eigenvalue of sum_i dN_i/dX (x) dN_i/dX
  double hourglass_gram_max;          // largest eigenvalue of the 4x4 Gram matrix of gamma
};

// The four hourglass patterns h_a of the hexahedron at its nodes (node order above):
// eta zeta, zeta xi, xi eta, xi eta zeta, each orthogonal to 1, X, Y and Z of the
// reference cube (Flanagan & Belytschko 1981, eq. 19).
inline constexpr double kHex8HourglassPattern[4][8] = {{1, 1, -1, -1, -1, -1, 1, 1},
                                                       {1, -1, -1, 1, -1, 1, 1, -1},
                                                       {1, -1, 1, -1, 1, -1, 1, -1},
                                                       {-1, 1, -1, 1, 1, -1, 1, -1}};

// Throws cosim::Error if the reference volume is not positive.
Hex8Reference hex8_reference(const double X[8][3]);

// Deformation gradient at the centroid, F = sum_i x_i (x) dN_i/dX.
Eigen::Matrix3d hex8_deformation_gradient(const Hex8Reference& ref, const double x[8][3]);

// Nodal internal forces of a hex from its Kirchhoff stress tau at the centroid:
//   f_i = V0 tau F^-T dN_i/dX     (= V0 P dN_i/dX, P the first Piola-Kirchhoff stress)
// plus the hourglass force  f_i += k sum_a gamma_ai q_a,  q_a = sum_j gamma_aj x_j,
// hourglass energy 0.5 k sum_a |q_a|^2, with stiffness
//   k = hourglass_coefficient * shear_modulus * V0 * sum_i |dN_i/dX|^2.
// For a cube of edge h, k = 1.5 c G h; c = 1/24 reproduces the exact pure-bending
// energy of the (xi eta) mode for nu = 1/2 (calibration in elements.cpp).
// f is the internal force (the gradient of the element's energy; it enters the
// equation of motion with a minus sign). Writes f (not accumulated). Returns the
// hourglass energy.
double hex8_internal_forces(const Hex8Reference& ref, const double x[8][3],
                            const Eigen::Matrix3d& F, const Eigen::Matrix3d& tau,
                            double hourglass_coefficient, double shear_modulus_Pa,
                            double f[8][3]);

// Critical time step 2 / omega_max of the element with lumped mass rho V / 8 per node,
// from the rigorous bound (Weyl inequality on the one-point and hourglass parts)
//   omega_max^2 <= (8 / rho) (max(3 K, 2 G) + E_fibre) lambda_max(sum_i B_i B_i^T)
//                  + 8 k lambda_max(Gamma Gamma^T) / (rho V),
// exact for a cube of nearly incompressible material. E_fibre = phi E of smeared rebar.
// By the element eigenvalue inequality it bounds the mesh step. No safety factor.
double hex8_stable_time_step_s(const Hex8Reference& ref, double density_kg_per_m3,
                               double bulk_modulus_Pa, double shear_modulus_Pa,
                               double hourglass_coefficient, double fibre_modulus_Pa = 0.0);

// Sharper bound for an element whose smeared rebar runs along the unit reference
// direction a0. The rebar adds the rank-one stiffness E_fibre V g g^T with
// g_(i,k) = (a0 . dN_i/dX) a0_k (one-point strain along the bar, Bathe, Finite Element
// Procedures, 2014, sec. 5.4), whose eigenvalue is E_fibre V sum_i (a0 . dN_i/dX)^2.
// In a thin belt or ply layer the bars lie in the layer, so this sees the in-plane
// element length instead of the layer thickness: the steel no longer sets the step
// through the thickness, where only rubber resists. The geometric stiffness of the bar
// tension has the same directional form times phi sigma_bar << E_fibre (strains below
// 1 %), left to the safety factor.
double hex8_stable_time_step_s(const Hex8Reference& ref, double density_kg_per_m3,
                               double bulk_modulus_Pa, double shear_modulus_Pa,
                               double hourglass_coefficient, double fibre_modulus_Pa,
                               const Eigen::Vector3d& fibre_direction);

// sum_i (a . dN_i/dX)^2 [1/m^2]: the squared gradient of the one-point strain along a.
double hex8_directional_gradient_sq_per_m2(const Hex8Reference& ref, const Eigen::Vector3d& a);

// Axisymmetric 4-node quadrilateral in the (r, y) plane with twist (CGAX4R-type, the
// Abaqus "generalized axisymmetric stress/displacement elements with twist"; Abaqus
// Theory Manual, section "Axisymmetric elements"), node order counter-clockwise.
// Each node has the dofs (r, y, phi): the material point at the reference
// (R, Y, Theta) moves to (r, y, Theta + phi), phi the twist angle about the symmetry
// axis [rad]. All integrals are per radian of circumference.
//
// Deformation gradient in the orthonormal (r, y, theta) bases (reference at Theta,
// current at Theta + phi), one-point at the centroid:
//   F = [[dr/dR,        dr/dY,        0        ],
//        [dy/dR,        dy/dY,        0        ],
//        [r_c dphi/dR,  r_c dphi/dY,  r_c / R_c]],
// d/dX = sum_i (.)_i dN_i/dX, r_c (R_c) the mean current (reference) node radius:
// x = r e_r(Theta + phi) + y e_y gives dx/dR = r_R e_r + y_R e_y + r phi_R e_theta and
// (1/R) dx/dTheta = (r/R) e_theta. Without twist (phi = 0) it is the CAX4R element.
//
// The twist dofs of nodes on the axis (R_i = 0) are meaningless (their hoop
// displacement R phi is 0): callers hold them, and the step bound leaves them out.
struct Quad4AxiReference {
  double dNdX[4][2];  // d/dR, d/dY at the centroid (exact area-mean gradient)
  double gamma[4];    // hourglass base vector, gamma = h - (h.X) B, h = (1, -1, 1, -1)
  double area_m2;
  double radius_m;           // R of the centroid (mean of the node radii)
  double volume_per_rad_m3;  // area * R
  double characteristic_length_m;   // area / longest edge (see quad4axi_stable_time_step_s)
  double gradient_sq_sum_per_m2;    // sum_i |dN_i/dX|^2
  double gradient_gram_max_per_m2;  // largest eigenvalue of sum_i dN_i/dX (x) dN_i/dX
  // The same for the twist dofs measured as hoop displacements w_i = R_i phi_i (the
  // coordinates whose lumped mass is m_i), s_i = R_c / R_i, nodes with R_i > 0 only:
  double twist_gradient_gram_max_per_m2;  // largest eigenvalue of sum_i s_i^2 B_i (x) B_i
  double twist_hourglass_sq;              // sum_i (s_i gamma_i)^2
};
// Throws cosim::Error if the area or the centroid radius is not positive.
Quad4AxiReference quad4axi_reference(const double X[4][2]);

// F in (r, y, theta) components (see above) from the current node positions (r, y)
// and twist angles phi [rad].
Eigen::Matrix3d quad4axi_deformation_gradient(const Quad4AxiReference& ref, const double x[4][2],
                                              const double twist_rad[4]);
// Without twist (all phi = 0): in-plane gradient plus the hoop stretch r_c / R_c.
Eigen::Matrix3d quad4axi_deformation_gradient(const Quad4AxiReference& ref, const double x[4][2]);

// Generalised nodal forces per radian from tau (in (r, y, theta) components), the
// exact gradient of V W(F) + E_hg with V = area * R_c and P = tau F^-T:
//   f_i     = V P_in dN_i/dX (in-plane rows r, y)
//           + (V / 4) (P_thR dphi/dR + P_thY dphi/dY + P_thth / R_c) e_r
//             (dF_th. / dr_i = N_i(centroid) (dphi/dR, dphi/dY, 1 / R_c), N_i = 1/4),
//   M_i     = V r_c (P_thR dN_i/dR + P_thY dN_i/dY)      (conjugate to phi_i [N m]),
// plus hourglass terms on the in-plane positions and on the hoop displacement
// R_c phi with one stiffness k = hourglass_coefficient * G * V * sum_i |dN_i/dX|^2:
//   E_hg = k (|q|^2 + R_c^2 q_phi^2) / 2,  q = sum_j gamma_j x_j,  q_phi = sum_j gamma_j phi_j,
//   f_i += k gamma_i q,   M_i += k R_c^2 gamma_i q_phi.
// gamma annihilates constant and linear fields, so a rigid rotation about the axis
// (uniform phi) and a uniform twist gradient give no hourglass force, and a uniform
// phi gives F and hence forces unchanged (sum_i dN_i/dX = 0). The twist hourglass
// uses the reference R_c so that it stays quadratic in phi and does not couple to r.
// F must be quad4axi_deformation_gradient(ref, x, twist_rad) (r_c and grad phi are
// read from it). Writes f and moment. Returns the hourglass energy.
double quad4axi_internal_forces(const Quad4AxiReference& ref, const double x[4][2],
                                const double twist_rad[4], const Eigen::Matrix3d& F,
                                const Eigen::Matrix3d& tau, double hourglass_coefficient,
                                double shear_modulus_Pa, double f[4][2], double moment_N_m[4]);
// Without twist (CAX4R): all phi = 0, F from the two-argument
// quad4axi_deformation_gradient; the moments are dropped.
double quad4axi_internal_forces(const Quad4AxiReference& ref, const double x[4][2],
                                const Eigen::Matrix3d& F, const Eigen::Matrix3d& tau,
                                double hourglass_coefficient, double shear_modulus_Pa,
                                double f[4][2]);

// Critical step bound of the axisymmetric quad with twist, lumped mass m = rho V / 4
// per node on (r, y) and rotational inertia m R_i^2 on phi (twist of nodes on the axis
// held). In the coordinates (u_r, u_y, w = R phi) the displacement gradient at the
// reference is H = sum_i u_i (x) B_i plus the hoop entry u_r / (4 R) and the twist
// entries H_thl = sum_i s_i w_i B_il; the three dof blocks map to disjoint entries of
// H, and the isotropic tangent does not couple the twist entries (shear only, modulus
// G) to the others, so
//   omega_max^2 <= (4 / rho) [max(max(3 K, 2 G) g_in, G g_tw) + E_fibre max(g_in, g_tw)]
//                  + 4 k max(|gamma|^2, sum_i (s_i gamma_i)^2) / (rho V),
// g_in = max(lambda_max(sum_i B_i B_i^T), 1 / (4 R^2)), g_tw = twist_gradient_gram_max.
double quad4axi_stable_time_step_s(const Quad4AxiReference& ref, double density_kg_per_m3,
                                   double bulk_modulus_Pa, double shear_modulus_Pa,
                                   double hourglass_coefficient, double fibre_modulus_Pa = 0.0);

}  // namespace tyre_fe
