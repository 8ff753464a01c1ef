// Constitutive kernels of the tyre (see materials.hpp). These run once per element
// per explicit step: fixed-size Eigen only, no allocation, no exceptions. An
// inverted material point (det F <= 0) yields NaN stress and energy so that the
// caller's finiteness check on the residual catches it outside the hot loop.
#include "tyre_fe/materials.hpp"

#include <cmath>
#include <limits>

#include <Eigen/LU>  // determinant

namespace tyre_fe {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::Matrix3d inverted_point(double* energy) {
  if (energy) *energy = kNaN;
  return Eigen::Matrix3d::Constant(kNaN);
}

// Yeoh, Abaqus Analysis User's Guide 22.5.1 (reduced polynomial, N = 3). With
// Bbar = J^(-2/3) F F^T, I1b = tr Bbar and x = I1b - 3 the Kirchhoff stress is
//   tau = 2 dU/dI1b dev(Bbar) + J dU/dJ I,
//   dU/dI1b = C10 + 2 C20 x + 3 C30 x^2,   J dU/dJ = (2/D1) J (J - 1) = K0 J (J - 1).
Eigen::Matrix3d yeoh_kirchhoff(const YeohRubber& m, const Eigen::Matrix3d& F, double* energy) {
  const double J = F.determinant();
  if (!(J > 0.0)) return inverted_point(energy);
  const Eigen::Matrix3d B = F * F.transpose();
  const double cbrt_J = std::cbrt(J);
  const double J_m23 = 1.0 / (cbrt_J * cbrt_J);
  const double trace_B = B.trace();
  const double x = J_m23 * trace_B - 3.0;
  const double dU_dI1b = m.C10_Pa + x * (2.0 * m.C20_Pa + 3.0 * m.C30_Pa * x);
  const double volumetric = m.bulk_modulus_Pa * J * (J - 1.0);

  Eigen::Matrix3d tau = (2.0 * dU_dI1b * J_m23) * B;
  const double diagonal = volumetric - 2.0 * dU_dI1b * J_m23 * trace_B / 3.0;
  tau(0, 0) += diagonal;
  tau(1, 1) += diagonal;
  tau(2, 2) += diagonal;
  if (energy) {
    // 1/D1 = K0 / 2.
    *energy = x * (m.C10_Pa + x * (m.C20_Pa + x * m.C30_Pa)) +
              0.5 * m.bulk_modulus_Pa * (J - 1.0) * (J - 1.0);
  }
  return tau;
}

// St. Venant-Kirchhoff: S = lambda tr(E) I + 2 mu E with E = (F^T F - I) / 2,
// tau = F S F^T, W = lambda/2 tr(E)^2 + mu E:E (Belytschko et al. 2000, 5.4.2).
Eigen::Matrix3d svk_kirchhoff(const ElasticSolid& m, const Eigen::Matrix3d& F, double* energy) {
  if (!(F.determinant() > 0.0)) return inverted_point(energy);
  const double nu = m.poisson_ratio;
  const double mu = m.youngs_modulus_Pa / (2.0 * (1.0 + nu));
  const double lambda = m.youngs_modulus_Pa * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  Eigen::Matrix3d E = 0.5 * (F.transpose() * F);
  E(0, 0) -= 0.5;
  E(1, 1) -= 0.5;
  E(2, 2) -= 0.5;
  const double trace_E = E.trace();
  Eigen::Matrix3d S = (2.0 * mu) * E;
  S(0, 0) += lambda * trace_E;
  S(1, 1) += lambda * trace_E;
  S(2, 2) += lambda * trace_E;
  if (energy) *energy = 0.5 * lambda * trace_E * trace_E + mu * E.squaredNorm();
  return F * S * F.transpose();
}

}  // namespace

double SolidMaterial::density_kg_per_m3() const {
  return kind == Kind::yeoh ? yeoh.density_kg_per_m3 : elastic.density_kg_per_m3;
}

double SolidMaterial::bulk_modulus_Pa() const {
  if (kind == Kind::yeoh) return yeoh.bulk_modulus_Pa;
  return elastic.youngs_modulus_Pa / (3.0 * (1.0 - 2.0 * elastic.poisson_ratio));
}

double SolidMaterial::shear_modulus_Pa() const {
  if (kind == Kind::yeoh) return yeoh.initial_shear_modulus_Pa();
  return elastic.youngs_modulus_Pa / (2.0 * (1.0 + elastic.poisson_ratio));
}

Eigen::Matrix3d kirchhoff_stress(const SolidMaterial& m, const Eigen::Matrix3d& F,
                                 double* energy) {
  return m.kind == SolidMaterial::Kind::yeoh ? yeoh_kirchhoff(m.yeoh, F, energy)
                                             : svk_kirchhoff(m.elastic, F, energy);
}

// Incompressible uniaxial tension: F = diag(l, l^-1/2, l^-1/2), the lateral stress
// fixes the pressure, leaving P = 2 (l - l^-2) dU/dI1 (Abaqus Analysis User's Guide
// 22.5.1, uniaxial test data; Ogden, Non-linear elastic deformations, 1984).
double yeoh_uniaxial_nominal_stress_Pa(const YeohRubber& m, double stretch) {
  const double x = stretch * stretch + 2.0 / stretch - 3.0;
  const double dU_dI1 = m.C10_Pa + 2.0 * m.C20_Pa * x + 3.0 * m.C30_Pa * x * x;
  return 2.0 * (stretch - 1.0 / (stretch * stretch)) * dU_dI1;
}

// W(lambda) = phi E (ln lambda)^2 / 2 with lambda = |F a0|; P = dW/dF =
// phi E ln(lambda) / lambda^2 (F a0) (x) a0, hence tau = P F^T = phi E ln(lambda) a (x) a.
double add_rebar_kirchhoff_stress(const Eigen::Vector3d& a0, double volume_fraction,
                                  double youngs_modulus_Pa, const Eigen::Matrix3d& F,
                                  Eigen::Matrix3d& tau) {
  const Eigen::Vector3d stretched = F * a0;
  const double stretch_sq = stretched.squaredNorm();
  if (!(stretch_sq > 0.0)) {
    tau.setConstant(kNaN);
    return kNaN;
  }
  const double log_stretch = 0.5 * std::log(stretch_sq);
  const double axial = volume_fraction * youngs_modulus_Pa * log_stretch;
  tau.noalias() += (axial / stretch_sq) * (stretched * stretched.transpose());
  return 0.5 * axial * log_stretch;
}

}  // namespace tyre_fe
