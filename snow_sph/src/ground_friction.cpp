// Coulomb friction of the container's walls on the snow next to them
// (docs/sph.md "The ground under the snow"). A COULOMB wall is a free-slip
// mirror (boundaries.cpp) plus, on each particle its mirror images reach, a
// tangential force opposing the particle's sliding:
//   - the wall's normal force on the particle is what the wall's images push
//     on it: the normal part of the pair forces (stress and artificial
//     viscosity, pair_forces.cpp) of its ghost neighbours over that wall, plus
//     the wall repulsion (boundaries.hpp) closer than dx/2. By the momentum
//     balance these add up to the wall's whole reaction (a block at rest on
//     the floor: its weight), wherever the SPH stress near a free edge is off;
//     a reaction taken from the particles' own stress at the wall instead
//     made a test block's friction 8 % high;
//   - the friction is the return mapping of explicit contact codes
//     (Wriggers 2006, Computational Contact Mechanics, 2nd ed., sec. 10.4;
//     Abaqus/Explicit's kinematic contact): the force that would stop the
//     particle's tangential velocity at the next kick (the trial, stick) if
//     it is within mu N, else mu N against the trial velocity (slip). The
//     friction therefore never reverses the sliding.
// The friction's work over the kick (force times the kick's mean tangential
// velocity) is booked as ground-friction dissipation.
#include <algorithm>
#include <cmath>

#include "cosim/parallel.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {
namespace {

bool any_coulomb_wall(const Model& m) {
  for (const MirrorPlane& plane : m.planes)
    if (plane.contact == WallContactKind::coulomb && !plane.symmetry) return true;
  return false;
}

double coordinate(const Particles& p, int axis, std::size_t i) {
  return axis == 0 ? p.x[i] : axis == 1 ? p.y[i] : p.z[i];
}

// What reads the pair forces of the step.
struct PairForceView {
  const NeighbourList& list;
  const PairRates& rates;
  const SymmetricField& q;  // sigma / rho^2 of every particle and ghost
};

// The push of the images over plane k on particle i, along the plane's inward
// normal [N] (>= 0), and the wall repulsion's.
double wall_normal_force_N(const Model& m, const PairForceView& view, std::size_t k, std::size_t i, double d) {
  const Particles& p = m.particles;
  const MirrorPlane& plane = m.planes[k];
  const int a = plane.axis;
  const double h = m.kernel.h, alpha = m.settings.av_alpha, beta = m.settings.av_beta;
  const SymmetricField& q = view.q;
  double push = 0.0;  // acceleration along the axis, pair terms as in pair_forces.cpp
  for (std::uint32_t e = view.list.offsets[i]; e < view.list.offsets[i + 1]; ++e) {
    const std::uint32_t j = view.list.index[e];
    if (j < p.n_real || !(p.ghost_planes[j] & (1u << k))) continue;
    const double r[3] = {p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]};
    const double f = view.rates.pair_f[e];
    const double grad[3] = {r[0] * f, r[1] * f, r[2] * f};
    const double row_xx = q.xx[i] + q.xx[j], row_yy = q.yy[i] + q.yy[j], row_zz = q.zz[i] + q.zz[j];
    const double row_xy = q.xy[i] + q.xy[j], row_yz = q.yz[i] + q.yz[j], row_xz = q.xz[i] + q.xz[j];
    const double stress = a == 0   ? row_xx * grad[0] + row_xy * grad[1] + row_xz * grad[2]
                          : a == 1 ? row_xy * grad[0] + row_yy * grad[1] + row_yz * grad[2]
                                   : row_xz * grad[0] + row_yz * grad[1] + row_zz * grad[2];
    const double vr = (p.vx[i] - p.vx[j]) * r[0] + (p.vy[i] - p.vy[j]) * r[1] + (p.vz[i] - p.vz[j]) * r[2];
    const double mu = h * std::min(vr, 0.0) * view.rates.pair_inv[e];
    const double visc = (-alpha * 0.5 * (p.sound_speed[i] + p.sound_speed[j]) * mu + beta * mu * mu) * 2.0 /
                        (p.density[i] + p.density[j]);
    push += p.mass[j] * (stress - visc * grad[a]);
  }
  double normal_N = std::max(0.0, plane.inside_sign * push * p.mass[i]);
  const double reach = m.particle_radius_m();
  if (d < reach) {  // the same push as wall_repulsion()
    const double s = (reach - std::max(d, 0.0)) / reach;
    normal_N += p.mass[i] * p.sound_speed[i] * p.sound_speed[i] / reach * s * s;
  }
  return normal_N;
}

// Applies plane k's friction to particle i; returns the work it dissipates
// over the next kick of length dt [J].
double apply_friction(const Model& m, const PairForceView& view, std::size_t k, std::size_t i, double dt,
                      double* a[3]) {
  const Particles& p = m.particles;
  const MirrorPlane& plane = m.planes[k];
  const double d = plane.inside_sign * (coordinate(p, plane.axis, i) - plane.position);
  if (d >= m.kernel.support) return 0.0;  // no image of this wall within reach
  const double v[3] = {p.vx[i], p.vy[i], p.vz[i]};
  double trial[3] = {0, 0, 0}, trial_speed2 = 0.0;
  for (int c = 0; c < 3; ++c) {
    if (c == plane.axis) continue;
    trial[c] = v[c] + dt * a[c][i];
    trial_speed2 += trial[c] * trial[c];
  }
  if (!(trial_speed2 > 0.0)) return 0.0;
  const double trial_speed = std::sqrt(trial_speed2);
  const double slip_limit = plane.friction_coefficient * wall_normal_force_N(m, view, k, i, d) / p.mass[i];
  const double friction = std::min(trial_speed / dt, slip_limit);  // stick, or slip at mu N
  double dissipated_J = 0.0;
  for (int c = 0; c < 3; ++c) {
    if (c == plane.axis) continue;
    const double direction = trial[c] / trial_speed;
    a[c][i] -= friction * direction;
    const double v_end = trial[c] - friction * dt * direction;
    dissipated_J += p.mass[i] * friction * dt * direction * 0.5 * (v[c] + v_end);
  }
  return dissipated_J;
}

}  // namespace

void ground_friction(Model& m, const NeighbourList& list, const PairRates& rates,
                     const SymmetricField& stress_over_rho2, double dt, std::vector<double>& dissipated_J) {
  if (!any_coulomb_wall(m)) return;
  Particles& p = m.particles;
  double* a[3] = {p.ax.data(), p.ay.data(), p.az.data()};
  const PairForceView view{list, rates, stress_over_rho2};
  cosim::parallel_for("walls.friction", p.n_real, [&](std::size_t i) {
    dissipated_J[i] = 0.0;
    if (!p.active[i]) return;  // at rest outside the active domain
    for (std::size_t k = 0; k < m.planes.size(); ++k)
      if (m.planes[k].contact == WallContactKind::coulomb && !m.planes[k].symmetry)
        dissipated_J[i] += apply_friction(m, view, k, i, dt, a);
  });
}

}  // namespace snow_sph
