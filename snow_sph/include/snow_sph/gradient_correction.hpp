#pragma once
// The corrected SPH velocity gradient (Randles & Libersky 1996, Comput. Methods
// Appl. Mech. Eng. 139, 375-408; Bonet & Lok 1999, Comput. Methods Appl. Mech.
// Eng. 180, 97-115), used when the scene sets sph.kernel_gradient_correction.
//
// The plain SPH gradient of particle i, (1/rho_i) sum_j m_j (v_j - v_i) (x) grad W,
// sees a linear field v = A x as A M with M = (1/rho_i) sum_j m_j (x_j - x_i) (x) grad W.
// M is the identity only for a complete, continuous neighbourhood: on a lattice it
// is a factor near 1 (tests/snow_sph/test_snow_oedometer.cpp), and where the support is cut
// (a free surface, a body's face) it loses up to half of the normal component. The
// corrected gradient L M^-1 is exact for every linear field.
#include <Eigen/Dense>

namespace snow_sph {

// l: the 3 x 3 sum  sum_j m_j (v_j - v_i) (x) grad W  (row-major; divided by rho_i
// it is the plain gradient); m: the symmetric  sum_j m_j (x_j - x_i) (x) grad W  as
// {xx, xy, xz, yy, yz, zz}. Replaces l by  rho_i L M^-1  (so that l / rho_i is the
// corrected gradient) and returns true, or leaves l as it is and returns false when
// M is too ill-conditioned to invert: det(M / s) below 0.01 with s = trace(M) / 3,
// a particle with neighbours on too few sides (a corner of a free surface, a
// particle flying alone).
inline bool correct_velocity_gradient(double* l, double rho_i, const double* m) {
  Eigen::Matrix3d M;
  M << m[0], m[1], m[2], m[1], m[3], m[4], m[2], m[4], m[5];
  const double scale = M.trace() / 3.0;
  if (!(scale > 0.0) || !((M / scale).determinant() > 0.01)) return false;
  Eigen::Matrix3d L;
  L << l[0], l[1], l[2], l[3], l[4], l[5], l[6], l[7], l[8];
  // L M^-1 is the gradient itself (the 1/rho_i of both sums cancels).
  const Eigen::Matrix3d corrected = rho_i * (L * (M / scale).inverse() / scale);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) l[3 * a + b] = corrected(a, b);
  return true;
}

}  // namespace snow_sph
