// One-point hexahedron and axisymmetric quadrilateral (with twist) with
// Flanagan-Belytschko hourglass stiffness (see elements.hpp).
//
// Gradient operator: the exact volume-mean gradient B_i = (1/V) int dN_i/dX dV
// (Flanagan & Belytschko 1981). It satisfies sum_i B_i = 0 and
// sum_i X_i (x) B_i = I exactly, so every affine field gives the exact F and the
// element passes the patch test on distorted meshes.
//
// Hourglass stiffness k = c G V0 sum_i |B_i|^2 (G the initial shear modulus). For a
// cube of edge h, V0 sum_i |B_i|^2 = 1.5 h. The (xi eta) x-mode of amplitude delta
// (q = 8 delta) is the element's picture of pure bending, which the one-point
// gradient does not see (F = I); the Euler-Bernoulli energy of the bending field
// with the same nodal values, u_x = 4 delta X Y / h^2, is (2/3) E delta^2 h, so the
// physical stiffness is k = E h / 48, i.e. c = 1/24 = 0.042 for nu = 1/2 (E = 3 G).
// This is the calibration idea of the assumed-strain stabilisation (Belytschko &
// Bindeman 1993, CMAME 105:225-260; Belytschko, Liu & Moran 2000, section 8.7). The
// default c = 0.05 is 1.2x that bending stiffness. In 2D (plane strain) the same c
// gives 0.3x the bending stiffness E h / (12 (1 - nu^2)) per unit thickness.
//
// Total form on current positions: q_a = sum_j gamma_aj x_j vanishes for every
// x = A X + t because gamma_a annihilates 1 and X (sum_j gamma_aj = 0 and
// sum_j gamma_aj X_j = 0), so rigid motions, including finite rotations, and
// homogeneous deformations give no hourglass force.
#include "tyre_fe/elements.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "cosim/error.hpp"
#include "cosim/quad_facet.hpp"

namespace tyre_fe {
namespace {

// Natural coordinates of the hex nodes (Abaqus C3D8 / VTK_HEXAHEDRON order).
constexpr double kXi[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
constexpr double kEta[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
constexpr double kZeta[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

// cof(A) = det(A) A^-T, from the columns: [a1 x a2, a2 x a0, a0 x a1].
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& A) {
  Eigen::Matrix3d C;
  C.col(0) = A.col(1).cross(A.col(2));
  C.col(1) = A.col(2).cross(A.col(0));
  C.col(2) = A.col(0).cross(A.col(1));
  return C;
}

// Largest squared frequency factor of the isotropic tangent at the reference
// state acting on the displacement gradient: lambda_max(C) = max(3K, 2G).
double max_modulus(double bulk_modulus_Pa, double shear_modulus_Pa) {
  return std::max(3.0 * bulk_modulus_Pa, 2.0 * shear_modulus_Pa);
}

}  // namespace

Hex8Reference hex8_reference(const double X[8][3]) {
  Hex8Reference ref{};
  // int dN_i/dX dV = int cof(J) dN_i/dxi dxi. cof(J) is quadratic and dN/dxi bilinear
  // in the other two coordinates, so 2x2x2 Gauss points integrate it exactly.
  const double g = 1.0 / std::sqrt(3.0);
  double integral[8][3] = {};
  double volume = 0.0;
  for (int p = 0; p < 8; ++p) {
    const double xi = g * kXi[p], eta = g * kEta[p], zeta = g * kZeta[p];
    double dN[8][3];
    for (int i = 0; i < 8; ++i) {
      dN[i][0] = 0.125 * kXi[i] * (1 + kEta[i] * eta) * (1 + kZeta[i] * zeta);
      dN[i][1] = 0.125 * kEta[i] * (1 + kXi[i] * xi) * (1 + kZeta[i] * zeta);
      dN[i][2] = 0.125 * kZeta[i] * (1 + kXi[i] * xi) * (1 + kEta[i] * eta);
    }
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();  // J_kl = dX_k / dxi_l
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) J(k, l) += X[i][k] * dN[i][l];
    const Eigen::Matrix3d C = cofactor(J);
    volume += J.col(0).dot(C.col(0));  // det J, Gauss weight 1
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d b = C * Eigen::Vector3d(dN[i][0], dN[i][1], dN[i][2]);
      for (int k = 0; k < 3; ++k) integral[i][k] += b[k];
    }
  }
  if (!(volume > 0.0))
    throw cosim::Error("hex8 element has non-positive volume " + cosim::number_text(volume) +
                       " m^3 (inverted or wrong node order)");
  ref.volume_m3 = volume;

  Eigen::Matrix3d gram = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) ref.dNdX[i][k] = integral[i][k] / volume;
    const Eigen::Vector3d b(ref.dNdX[i][0], ref.dNdX[i][1], ref.dNdX[i][2]);
    gram += b * b.transpose();
  }
  ref.gradient_sq_sum_per_m2 = gram.trace();
  ref.gradient_gram_max_per_m2 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(gram).eigenvalues()(2);

  // Flanagan-Belytschko base vectors gamma_a = h_a - (h_a . X_k) B_k (their 1/8
  // normalisation dropped), h_a = eta zeta, zeta xi, xi eta, xi eta zeta.
  for (int a = 0; a < 4; ++a) {
    const double* h = kHex8HourglassPattern[a];
    double hX[3] = {0, 0, 0};
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) hX[k] += h[i] * X[i][k];
    for (int i = 0; i < 8; ++i)
      ref.gamma[a][i] = h[i] - hX[0] * ref.dNdX[i][0] - hX[1] * ref.dNdX[i][1] - hX[2] * ref.dNdX[i][2];
  }
  Eigen::Matrix4d hourglass_gram;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      double s = 0.0;
      for (int i = 0; i < 8; ++i) s += ref.gamma[a][i] * ref.gamma[b][i];
      hourglass_gram(a, b) = s;
    }
  ref.hourglass_gram_max = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(hourglass_gram).eigenvalues()(3);

  double max_face_area = 0.0;
  for (const auto& face : kHexFaces) {
    Eigen::Vector3d d1, d2;  // diagonals: area of a (possibly warped) quad = |d1 x d2| / 2
    for (int k = 0; k < 3; ++k) {
      d1[k] = X[face[2]][k] - X[face[0]][k];
      d2[k] = X[face[3]][k] - X[face[1]][k];
    }
    max_face_area = std::max(max_face_area, cosim::quad_area_vector_from_diagonals(d1, d2).norm());
  }
  ref.characteristic_length_m = volume / max_face_area;
  return ref;
}

Eigen::Matrix3d hex8_deformation_gradient(const Hex8Reference& ref, const double x[8][3]) {
  double F[3][3] = {};
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) F[k][l] += x[i][k] * ref.dNdX[i][l];
  Eigen::Matrix3d out;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) out(k, l) = F[k][l];
  return out;
}

double hex8_internal_forces(const Hex8Reference& ref, const double x[8][3],
                            const Eigen::Matrix3d& F, const Eigen::Matrix3d& tau,
                            double hourglass_coefficient, double shear_modulus_Pa,
                            double f[8][3]) {
  // V0 P = V0 tau F^-T = (V0 / det F) tau cof(F).
  const Eigen::Matrix3d C = cofactor(F);
  const double scale = ref.volume_m3 / F.col(0).dot(C.col(0));
  const Eigen::Matrix3d VP = scale * (tau * C);
  double P[3][3];
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) P[k][l] = VP(k, l);
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k)
      f[i][k] = P[k][0] * ref.dNdX[i][0] + P[k][1] * ref.dNdX[i][1] + P[k][2] * ref.dNdX[i][2];

  const double k_hg =
      hourglass_coefficient * shear_modulus_Pa * ref.volume_m3 * ref.gradient_sq_sum_per_m2;
  double q[4][3] = {};
  for (int a = 0; a < 4; ++a)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 3; ++k) q[a][k] += ref.gamma[a][j] * x[j][k];
  double energy = 0.0;
  for (int a = 0; a < 4; ++a) {
    energy += q[a][0] * q[a][0] + q[a][1] * q[a][1] + q[a][2] * q[a][2];
    for (int k = 0; k < 3; ++k) q[a][k] *= k_hg;
  }
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k)
      f[i][k] += ref.gamma[0][i] * q[0][k] + ref.gamma[1][i] * q[1][k] +
                 ref.gamma[2][i] * q[2][k] + ref.gamma[3][i] * q[3][k];
  return 0.5 * k_hg * energy;
}

double hex8_stable_time_step_s(const Hex8Reference& ref, double density_kg_per_m3,
                               double bulk_modulus_Pa, double shear_modulus_Pa,
                               double hourglass_coefficient, double fibre_modulus_Pa) {
  // No direction: the rebar term takes the largest gradient eigenvalue (any direction).
  return hex8_stable_time_step_s(ref, density_kg_per_m3, bulk_modulus_Pa, shear_modulus_Pa,
                                 hourglass_coefficient, fibre_modulus_Pa, Eigen::Vector3d::Zero());
}

double hex8_directional_gradient_sq_per_m2(const Hex8Reference& ref, const Eigen::Vector3d& a) {
  double sum = 0.0;
  for (int i = 0; i < 8; ++i) {
    const double g = a[0] * ref.dNdX[i][0] + a[1] * ref.dNdX[i][1] + a[2] * ref.dNdX[i][2];
    sum += g * g;
  }
  return sum;
}

double hex8_stable_time_step_s(const Hex8Reference& ref, double density_kg_per_m3,
                               double bulk_modulus_Pa, double shear_modulus_Pa,
                               double hourglass_coefficient, double fibre_modulus_Pa,
                               const Eigen::Vector3d& fibre_direction) {
  const double k_hg =
      hourglass_coefficient * shear_modulus_Pa * ref.volume_m3 * ref.gradient_sq_sum_per_m2;
  const double a_norm = fibre_direction.norm();
  const double fibre_gradient_sq =
      a_norm > 0.0 ? hex8_directional_gradient_sq_per_m2(ref, fibre_direction / a_norm)
                   : ref.gradient_gram_max_per_m2;
  const double omega_sq =
      8.0 / density_kg_per_m3 *
      (max_modulus(bulk_modulus_Pa, shear_modulus_Pa) * ref.gradient_gram_max_per_m2 +
       fibre_modulus_Pa * fibre_gradient_sq + k_hg * ref.hourglass_gram_max / ref.volume_m3);
  return 2.0 / std::sqrt(omega_sq);
}

Quad4AxiReference quad4axi_reference(const double X[4][2]) {
  Quad4AxiReference ref{};
  double twice_area = 0.0;  // shoelace
  double radius = 0.0;
  for (int i = 0; i < 4; ++i) {
    const int n = (i + 1) % 4;
    twice_area += X[i][0] * X[n][1] - X[n][0] * X[i][1];
    radius += 0.25 * X[i][0];
  }
  if (!(twice_area > 0.0))
    throw cosim::Error("quad4axi element has non-positive area " + std::to_string(0.5 * twice_area) +
                       " m^2 (nodes must be counter-clockwise in (r, y))");
  if (!(radius > 0.0))
    throw cosim::Error("quad4axi element centroid radius " + std::to_string(radius) +
                       " m is not positive (the hoop stretch r/R needs R > 0)");
  ref.area_m2 = 0.5 * twice_area;
  ref.radius_m = radius;
  ref.volume_per_rad_m3 = ref.area_m2 * radius;
  // Mean gradient of the bilinear quad (Flanagan & Belytschko 1981):
  // A dN_i/dR = (Y_{i+1} - Y_{i-1}) / 2,  A dN_i/dY = (R_{i-1} - R_{i+1}) / 2.
  for (int i = 0; i < 4; ++i) {
    const int n = (i + 1) % 4, p = (i + 3) % 4;
    ref.dNdX[i][0] = (X[n][1] - X[p][1]) / twice_area;
    ref.dNdX[i][1] = (X[p][0] - X[n][0]) / twice_area;
  }
  Eigen::Matrix2d gram = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d b(ref.dNdX[i][0], ref.dNdX[i][1]);
    gram += b * b.transpose();
  }
  ref.gradient_sq_sum_per_m2 = gram.trace();
  ref.gradient_gram_max_per_m2 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(gram).eigenvalues()(1);

  constexpr double h[4] = {1, -1, 1, -1};
  double hR = 0.0, hY = 0.0;
  for (int i = 0; i < 4; ++i) {
    hR += h[i] * X[i][0];
    hY += h[i] * X[i][1];
  }
  for (int i = 0; i < 4; ++i) ref.gamma[i] = h[i] - hR * ref.dNdX[i][0] - hY * ref.dNdX[i][1];

  // Twist dofs as hoop displacements w_i = R_i phi_i: F_thl = r_c sum_i phi_i B_il =
  // sum_i s_i w_i B_il at the reference, s_i = R_c / R_i (nodes on the axis held).
  Eigen::Matrix2d twist_gram = Eigen::Matrix2d::Zero();
  ref.twist_hourglass_sq = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (!(X[i][0] > 0.0)) continue;
    const double s = radius / X[i][0];
    const Eigen::Vector2d b(s * ref.dNdX[i][0], s * ref.dNdX[i][1]);
    twist_gram += b * b.transpose();
    ref.twist_hourglass_sq += s * s * ref.gamma[i] * ref.gamma[i];
  }
  ref.twist_gradient_gram_max_per_m2 =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(twist_gram).eigenvalues()(1);

  double longest_edge = 0.0;
  for (int i = 0; i < 4; ++i) {
    const int n = (i + 1) % 4;
    longest_edge = std::max(longest_edge, std::hypot(X[n][0] - X[i][0], X[n][1] - X[i][1]));
  }
  ref.characteristic_length_m = ref.area_m2 / longest_edge;
  return ref;
}

Eigen::Matrix3d quad4axi_deformation_gradient(const Quad4AxiReference& ref, const double x[4][2],
                                              const double twist_rad[4]) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  double r_centroid = 0.0, twist_R = 0.0, twist_Y = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 2; ++k)
      for (int l = 0; l < 2; ++l) F(k, l) += x[i][k] * ref.dNdX[i][l];
    r_centroid += 0.25 * x[i][0];
    twist_R += twist_rad[i] * ref.dNdX[i][0];
    twist_Y += twist_rad[i] * ref.dNdX[i][1];
  }
  F(2, 0) = r_centroid * twist_R;       // hoop displacement gradient r dphi/dR
  F(2, 1) = r_centroid * twist_Y;       // and r dphi/dY
  F(2, 2) = r_centroid / ref.radius_m;  // hoop stretch of the centroid's circle
  return F;
}

Eigen::Matrix3d quad4axi_deformation_gradient(const Quad4AxiReference& ref, const double x[4][2]) {
  constexpr double no_twist[4] = {0.0, 0.0, 0.0, 0.0};
  return quad4axi_deformation_gradient(ref, x, no_twist);
}

double quad4axi_internal_forces(const Quad4AxiReference& ref, const double x[4][2],
                                const double twist_rad[4], const Eigen::Matrix3d& F,
                                const Eigen::Matrix3d& tau, double hourglass_coefficient,
                                double shear_modulus_Pa, double f[4][2], double moment_N_m[4]) {
  // V P with P = tau F^-T. F = [[A, 0], [c^T, s]] (A the in-plane 2x2 block,
  // c = r_c grad phi, s = F_thth), so F^-T = [[A^-T, -A^-T c / s], [0, 1 / s]]:
  //   P_kl = tau_k0 G_0l + tau_k1 G_1l (l = R, Y),  G = A^-T,
  //   P_k,th = (tau_k,th - tau_k0 (G c)_0 - tau_k1 (G c)_1) / s.
  const double V = ref.volume_per_rad_m3;
  const double inv_det2 = 1.0 / (F(0, 0) * F(1, 1) - F(0, 1) * F(1, 0));
  // A^-T = [[F11, -F10], [-F01, F00]] / det A.
  const double G00 = F(1, 1) * inv_det2, G01 = -F(1, 0) * inv_det2;
  const double G10 = -F(0, 1) * inv_det2, G11 = F(0, 0) * inv_det2;
  const double P00 = V * (tau(0, 0) * G00 + tau(0, 1) * G10);
  const double P01 = V * (tau(0, 0) * G01 + tau(0, 1) * G11);
  const double P10 = V * (tau(1, 0) * G00 + tau(1, 1) * G10);
  const double P11 = V * (tau(1, 0) * G01 + tau(1, 1) * G11);
  const double P20 = V * (tau(2, 0) * G00 + tau(2, 1) * G10);  // V P_thR
  const double P21 = V * (tau(2, 0) * G01 + tau(2, 1) * G11);  // V P_thY
  const double Gc0 = G00 * F(2, 0) + G01 * F(2, 1), Gc1 = G10 * F(2, 0) + G11 * F(2, 1);
  const double P22 = V * (tau(2, 2) - tau(2, 0) * Gc0 - tau(2, 1) * Gc1) / F(2, 2);  // V P_thth

  // r_c = R_c F_thth and r_c grad(phi) = (F_thR, F_thY), F being consistent with (x, phi).
  const double r_centroid = ref.radius_m * F(2, 2);
  // d(F_thR, F_thY, F_thth) / d r_i = (dphi/dR, dphi/dY, 1 / R_c) / 4.
  const double hoop = 0.25 * ((P20 * F(2, 0) + P21 * F(2, 1)) / r_centroid + P22 / ref.radius_m);

  const double k_hg =
      hourglass_coefficient * shear_modulus_Pa * V * ref.gradient_sq_sum_per_m2;
  double q[2] = {0.0, 0.0}, q_twist = 0.0;
  for (int j = 0; j < 4; ++j) {
    q[0] += ref.gamma[j] * x[j][0];
    q[1] += ref.gamma[j] * x[j][1];
    q_twist += ref.gamma[j] * twist_rad[j];
  }
  const double k_twist = k_hg * ref.radius_m * ref.radius_m;  // on w = R_c phi
  for (int i = 0; i < 4; ++i) {
    const double bR = ref.dNdX[i][0], bY = ref.dNdX[i][1], g = ref.gamma[i];
    f[i][0] = P00 * bR + P01 * bY + hoop + k_hg * g * q[0];
    f[i][1] = P10 * bR + P11 * bY + k_hg * g * q[1];
    moment_N_m[i] = r_centroid * (P20 * bR + P21 * bY) + k_twist * g * q_twist;
  }
  return 0.5 * (k_hg * (q[0] * q[0] + q[1] * q[1]) + k_twist * q_twist * q_twist);
}

double quad4axi_internal_forces(const Quad4AxiReference& ref, const double x[4][2],
                                const Eigen::Matrix3d& F, const Eigen::Matrix3d& tau,
                                double hourglass_coefficient, double shear_modulus_Pa,
                                double f[4][2]) {
  constexpr double no_twist[4] = {0.0, 0.0, 0.0, 0.0};
  double moment[4];
  return quad4axi_internal_forces(ref, x, no_twist, F, tau, hourglass_coefficient,
                                  shear_modulus_Pa, f, moment);
}

double quad4axi_stable_time_step_s(const Quad4AxiReference& ref, double density_kg_per_m3,
                                   double bulk_modulus_Pa, double shear_modulus_Pa,
                                   double hourglass_coefficient, double fibre_modulus_Pa) {
  const double V = ref.volume_per_rad_m3;
  const double k_hg = hourglass_coefficient * shear_modulus_Pa * V * ref.gradient_sq_sum_per_m2;
  double gamma_sq = 0.0;
  for (double g : ref.gamma) gamma_sq += g * g;
  // The hoop strain adds the gradient (1/4R, ..., 1/4R) on the r dofs; it is orthogonal
  // to the in-plane gradients (sum_i B_i = 0), so the Gram matrix gains 1/(4 R^2).
  const double gram_in_plane =
      std::max(ref.gradient_gram_max_per_m2, 0.25 / (ref.radius_m * ref.radius_m));
  // Twist block (entries F_thR, F_thY): the isotropic tangent sees only their shear,
  // W = G (H_thR^2 + H_thY^2) / 2, and does not couple them to the other entries.
  const double gram_twist = ref.twist_gradient_gram_max_per_m2;
  const double omega_sq =
      4.0 / density_kg_per_m3 *
      (std::max(max_modulus(bulk_modulus_Pa, shear_modulus_Pa) * gram_in_plane,
                shear_modulus_Pa * gram_twist) +
       fibre_modulus_Pa * std::max(gram_in_plane, gram_twist) +
       k_hg * std::max(gamma_sq, ref.twist_hourglass_sq) / V);
  return 2.0 / std::sqrt(omega_sq);
}

}  // namespace tyre_fe
