#pragma once
// Constitutive kernels of the tyre: Yeoh rubber, St. Venant-Kirchhoff steel and
// smeared rebar. Each works on one material point: deformation gradient in,
// Kirchhoff stress (tau = J sigma) and strain energy per reference volume out.
#include <Eigen/Core>

namespace tyre_fe {

// Reduced polynomial, N = 3 (Yeoh 1993; Abaqus Analysis User's Guide 22.5.1):
//   U = C10 (I1b - 3) + C20 (I1b - 3)^2 + C30 (I1b - 3)^3 + (1/D1) (J - 1)^2,
// I1b = J^(-2/3) tr(F F^T), K0 = 2 / D1, mu0 = 2 C10.
struct YeohRubber {
  double C10_Pa = 0.0;
  double C20_Pa = 0.0;
  double C30_Pa = 0.0;
  double bulk_modulus_Pa = 0.0;  // K0 (the thesis gives none; scenes state K0/mu0)
  double density_kg_per_m3 = 0.0;
  double initial_shear_modulus_Pa() const { return 2.0 * C10_Pa; }
};

// St. Venant-Kirchhoff (linear elasticity in Green strain, exact under large rotation):
// for the steel bead.
struct ElasticSolid {
  double youngs_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;
  double density_kg_per_m3 = 0.0;
};

// One of the two, chosen per region.
struct SolidMaterial {
  enum class Kind { yeoh, elastic } kind = Kind::yeoh;
  YeohRubber yeoh;
  ElasticSolid elastic;
  double density_kg_per_m3() const;
  // Small-strain moduli at the reference state (for the stable time step and
  // hourglass stiffness).
  double bulk_modulus_Pa() const;
  double shear_modulus_Pa() const;
};

// Kirchhoff stress tau = J sigma for deformation gradient F (det F > 0). Writes
// the strain energy per reference volume to *energy if not null.
Eigen::Matrix3d kirchhoff_stress(const SolidMaterial& m, const Eigen::Matrix3d& F,
                                 double* energy = nullptr);

// Closed forms used by the tests (incompressible uniaxial tension, Yeoh):
// nominal stress P = 2 (lambda - lambda^-2) dU/dI1, I1 = lambda^2 + 2/lambda.
double yeoh_uniaxial_nominal_stress_Pa(const YeohRubber& m, double stretch);

// Smeared rebar (Abaqus *REBAR LAYER, embedded): bars along the reference unit
// direction a0, volume fraction phi = area / (spacing * layer thickness), Young's
// modulus E, logarithmic bar strain. With lambda = |F a0| and a = F a0 / lambda:
//   W = phi E (ln lambda)^2 / 2,  tau = phi E ln(lambda) a (x) a.
// Adds tau to `tau` and returns W (per reference volume of the host element).
double add_rebar_kirchhoff_stress(const Eigen::Vector3d& a0, double volume_fraction,
                                  double youngs_modulus_Pa, const Eigen::Matrix3d& F,
                                  Eigen::Matrix3d& tau);

}  // namespace tyre_fe
