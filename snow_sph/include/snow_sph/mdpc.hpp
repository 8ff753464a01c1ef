#pragma once
// Modified Drucker-Prager/Cap plasticity for snow (thesis section 1.5,
// eqs 1.6-1.10; Abaqus Analysis User's Guide 23.3.2 "Modified Drucker-Prager/
// Cap model", Abaqus/Explicit variant: K = 1, d and beta given in the p-q plane).
//
//   shear failure (1.6):  Fs = q - p tan(beta) - d
//   transition    (1.8):  Ft = sqrt((p - pa)^2 + [q - (1 - alpha/cos beta)(d + pa tan beta)]^2)
//                              - alpha (d + pa tan beta)
//   cap           (1.9):  Fc = sqrt((p - pa)^2 + [R q / (1 + alpha - alpha/cos beta)]^2)
//                              - R (d + pa tan beta)
//   potential    (1.10):  Gs = sqrt([(pa - p) tan beta]^2 + [q / (1 + alpha - alpha/cos beta)]^2)
//                         (shear and transition, non-associated); Gc = Fc (cap, associated)
//   hardening:            pb(eps_vol_pl) from a piecewise linear table,
//                         pb = pa + R (d + pa tan beta)
//
// Sign conventions: stress and strain tension positive (Cauchy stress); p is
// the pressure (compression positive); eps_vol_pl is the volumetric plastic
// strain, compaction positive (the sign of the hardening table).
#include <Eigen/Dense>
#include <vector>

namespace snow_sph {

struct MdpcParameters {
  double youngs_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;
  double cohesion_Pa = 0.0;                            // d, in the p-q plane
  double friction_angle_rad = 0.0;                     // beta, in the p-q plane
  double cap_eccentricity = 0.0;                       // R
  double initial_cap_volumetric_plastic_strain = 0.0;  // eps_vol_pl_0
  double transition_alpha = 0.0;                       // alpha (0 for the thesis snow)
  double flow_stress_ratio_K = 1.0;                    // must be 1 (Abaqus/Explicit): t = q
  std::vector<double> hardening_pressure_Pa;                // pb, strictly increasing
  std::vector<double> hardening_volumetric_plastic_strain;  // strictly increasing, same length

  double bulk_modulus_Pa() const;   // E / (3 (1 - 2 nu))
  double shear_modulus_Pa() const;  // E / (2 (1 + nu))
  // pb(eps): piecewise linear in the table; below the first point the first
  // pressure; beyond the last point extrapolated with the last slope.
  double cap_hydrostatic_yield_Pa(double eps_vol_pl) const;
  // pa from pb = pa + R (d + pa tan beta)  (Abaqus 23.3.2, cap hardening).
  double cap_pa_Pa(double eps_vol_pl) const;
};

// Throws std::invalid_argument with a message naming the offending parameter
// (K != 1, tables empty/unsorted/of unequal length, nu outside [0, 0.5), E <= 0,
// beta outside [0, pi/2), R <= 0, d < 0, alpha outside [0, 1) or too large for
// beta, non-finite values, a cap whose apex q = d + pa tan beta is not positive).
void check_parameters(const MdpcParameters& params);

struct MdpcStepResult {
  double plastic_work_density_J_per_m3;  // sigma_{n+1} : d eps_p for this increment
  int surface;  // 0 elastic, 1 shear, 2 cap, 3 transition, 4 tension apex, -1 non-finite input
};

// One constitutive increment at a material point (elastic predictor, implicit
// return mapping in the p-q plane; see mdpc.cpp for the algorithm).
//   stress:            Cauchy, tension positive, already rotated objectively by the caller (in/out)
//   strain_increment:  symmetric rate of deformation * dt, tension positive
//   eps_vol_pl:        hardening variable, compaction positive (in/out)
// No allocation, no exceptions, no I/O: safe to call from an OpenMP loop.
// Non-finite input leaves stress and eps_vol_pl unchanged and returns surface -1.
// Parameters are assumed valid (call check_parameters once beforehand).
MdpcStepResult mdpc_update(const MdpcParameters& params, const Eigen::Matrix3d& strain_increment,
                           Eigen::Matrix3d& stress, double& eps_vol_pl);

// Smallest eps_vol_pl >= params.initial_cap_volumetric_plastic_strain for which
// the given stress is inside or on the cap (Fc <= 0, or p <= pa where the cap
// does not apply). Used to start a geostatically loaded layer on its yield
// surface instead of outside it. The returned value always gives Fc <= 0.
double cap_strain_enclosing(const MdpcParameters& params, const Eigen::Matrix3d& stress);

// The geostatic state of a laterally confined elastic layer under the vertical
// stress sigma_v (< 0 in compression; rho g depth below the top): the
// horizontal stress K0 sigma_v, K0 = nu / (1 - nu), and the cap hardening that
// encloses that stress (cap_strain_enclosing). The SPH blocks and the
// finite-element plate start from it.
struct ConfinedLayerState {
  double horizontal_stress_Pa;
  double eps_vol_pl;
};
ConfinedLayerState confined_layer_state(const MdpcParameters& params, double vertical_stress_Pa);

// Invariants and yield-function values for tests and diagnostics: p (pressure,
// compression positive), q (Mises), Fs (eq 1.6), Fc (eq 1.9) and pa for the
// given hardening state.
struct MdpcInvariants {
  double p_Pa, q_Pa, shear_Fs_Pa, cap_Fc_Pa, pa_Pa;
};
MdpcInvariants mdpc_invariants(const MdpcParameters& params, const Eigen::Matrix3d& stress,
                               double eps_vol_pl);

}  // namespace snow_sph
