#pragma once
// Penalty contact with Coulomb friction: the kernels every contact of the
// project is built from (SPH particles on rigid bodies, the tyre's nodes on the
// rigid road, SPH particles on the tyre's facets). Each caller keeps its own
// geometry (depth, normal, relative velocity) and its own named damping ratio;
// these functions are the law.
//
// Normal: a linear spring-dashpot that never pulls, f_n = max(0, k d - c v_n),
// with v_n the relative normal velocity (negative while approaching) and
// c = 2 zeta sqrt(k m) at a fraction zeta of critical damping. Where the damper
// acts is a named choice, because the two choices dissipate differently (a
// particle arriving at v leaves at e v):
//   Damping::approach_only   e = exp(-zeta acos(zeta) / sqrt(1 - zeta^2))
//     (damped quarter period in, undamped out);
//   Damping::both_ways       e = exp(-zeta (pi - atan(2 zeta sqrt(1 - zeta^2) /
//     (1 - 2 zeta^2))) / sqrt(1 - zeta^2)) for zeta < 1/sqrt(2): the force
//     reaches zero before the spring is unloaded and the particle leaves then
//     (Schwager and Poeschel, Granular Matter 9, 2007, 465).
// Neither is the unclamped e = exp(-zeta pi / sqrt(1 - zeta^2)).
//
// Tangential: Coulomb friction with an elastic stick (penalty regularisation,
// Wriggers, Computational Contact Mechanics, 2006, 5.2.2): a trial spring force
// is kept while inside the cone |f_t| <= mu f_n and scaled back onto the cone
// otherwise (the return map); the excess is slip. Or, for a body that should
// not creep at all, the friction that stops the relative sliding in one step
// (velocity_stop_friction).
//
// Every function is a few floating-point operations written in the order the
// contacts always used, so that moving them here changed no result.
#include <algorithm>
#include <cmath>

namespace cosim::penalty {

// Damper coefficient at `damping_ratio` of critical for a mass on a spring:
// c = 2 zeta sqrt(k m) (N s/m).
inline double damping_coefficient(double damping_ratio, double stiffness_N_per_m, double mass_kg) {
  return 2.0 * damping_ratio * std::sqrt(stiffness_N_per_m * mass_kg);
}

// Where the normal damper acts (see the header comment for what each dissipates).
enum class Damping {
  approach_only,  // only while the bodies approach (v_n < 0)
  both_ways,      // approaching and separating; the force is still clamped at zero
};

struct NormalForce {
  double force_N = 0.0;   // f_n >= 0, pushing the bodies apart
  double damper_N = 0.0;  // the damper's force while approaching (c |v_n|), 0 otherwise
};

// Normal force for penetration `depth_m` (> 0 in contact) at relative normal
// velocity `normal_velocity_m_per_s` (< 0 approaching), stiffness k and damper c.
inline NormalForce normal_force(double stiffness_N_per_m, double depth_m, double normal_velocity_m_per_s,
                                double damper_N_s_per_m, Damping damping) {
  const double vn = normal_velocity_m_per_s;
  NormalForce n;
  n.damper_N = vn < 0.0 ? -damper_N_s_per_m * vn : 0.0;
  if (damping == Damping::approach_only)
    n.force_N = std::max(0.0, stiffness_N_per_m * depth_m + n.damper_N);
  else
    n.force_N = std::max(0.0, stiffness_N_per_m * depth_m - damper_N_s_per_m * vn);
  return n;
}

// Power the normal damper dissipates while approaching (W): its force, at most
// the whole normal force (the clamp), times the approach speed.
inline double approach_damping_power(const NormalForce& n, double normal_velocity_m_per_s) {
  return std::min(n.damper_N, n.force_N) * std::max(-normal_velocity_m_per_s, 0.0);
}

// Coulomb return map of an elastic stick. `trial_N` is the magnitude of the
// trial tangential spring force, `cap_N` = mu f_n the radius of the cone.
// Sticking (trial <= cap) keeps the trial force; sliding scales it by `scale`
// onto the cone (0 if the cone is a point).
struct CoulombCap {
  bool sliding = false;
  double scale = 1.0;
};
inline CoulombCap coulomb_cap(double trial_N, double cap_N) {
  if (trial_N > cap_N) return {true, trial_N > 0.0 ? cap_N / trial_N : 0.0};
  return {false, 1.0};
}

// Energy a slip dissipates (J): the spring of stiffness kt is held at the cap
// while its anchor moves by the excess (trial - cap) / kt, against mu f_n = cap.
inline double slip_dissipation(double trial_N, double cap_N, double tangential_stiffness_N_per_m) {
  return cap_N * (trial_N - cap_N) / tangential_stiffness_N_per_m;
}

// Friction magnitude that stops a tangential relative speed vt of a mass m in
// one step dt, at most the cap mu f_n (no stick spring; the force opposes the
// relative tangential velocity). It dissipates f_t vt dt.
inline double velocity_stop_friction(double cap_N, double mass_kg, double tangential_speed_m_per_s, double dt_s) {
  return std::min(cap_N, mass_kg * tangential_speed_m_per_s / dt_s);
}

}  // namespace cosim::penalty
