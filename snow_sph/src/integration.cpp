// Integration: the kick and drift of the central-difference scheme (leapfrog
// with half-step velocities), including a coupled surface's force held on the
// particles over a coupling window (docs/coupling.md, "The terrain sub-steps").
#include "cosim/parallel.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {

KickLengths kick_lengths(std::uint64_t steps, double dt_prev, double dt, bool surface_held) {
  KickLengths k;
  // Kick: v^{n+1/2} = v^{n-1/2} + a^n (dt_prev + dt)/2 (first step: half kick).
  const double kick = steps == 0 ? 0.5 * dt : 0.5 * (dt_prev + dt);
  // The coupled surface's force in a^n is kicked with this step's length, not
  // the mean of two: it is held over the window's steps, which change length
  // from window to window when the terrain sub-steps, and its impulse over a
  // window must be the window times the force (for equal steps the two agree).
  const double surface_kick = steps == 0 ? kick : dt;
  const double extra = surface_held ? surface_kick - kick : 0.0;
  k.kick = kick, k.surface = surface_kick, k.extra = extra;
  return k;
}

// Work of the coupled surface's forces of the last exchange over this kick,
// with the mean of the velocities before and after it (the central-difference
// work; the velocity before alone books F^2 dt^2 / 2m too little a step, which
// grows with the step: docs/coupling.md).
double held_surface_work(const Particles& p, const ActiveDomain& domain, const KickLengths& k) {
  const double kick = k.kick, surface_kick = k.surface, extra = k.extra;
  double work = 0.0;
  auto contact_work = [&](std::size_t i) {
    const double fx = p.surface_fx[i], fy = p.surface_fy[i], fz = p.surface_fz[i];
    if (fx == 0.0 && fy == 0.0 && fz == 0.0) return 0.0;
    const double c = 0.5 * extra / p.mass[i];
    const double mx = p.vx[i] + 0.5 * kick * p.ax[i] + c * fx, my = p.vy[i] + 0.5 * kick * p.ay[i] + c * fy,
                 mz = p.vz[i] + 0.5 * kick * p.az[i] + c * fz;
    return surface_kick * (fx * mx + fy * my + fz * mz);
  };
  if (domain.on)
    for (std::uint32_t i : domain.move_list) work += contact_work(i);
  else
    for (std::size_t i = 0; i < p.n_real; ++i) work += contact_work(i);
  return work;
}

void kick_drift(Particles& p, const ActiveDomain& domain, const KickLengths& k, double dt) {
  const double kick = k.kick, extra = k.extra;
  const std::vector<std::uint32_t>& move_list = domain.move_list;
  auto kick_drift = [&](std::size_t i) {
    p.vx[i] += kick * p.ax[i], p.vy[i] += kick * p.ay[i], p.vz[i] += kick * p.az[i];
    p.x[i] += dt * p.vx[i], p.y[i] += dt * p.vy[i], p.z[i] += dt * p.vz[i];
  };
  auto kick_held_drift = [&](std::size_t i) {
    const double c = extra / p.mass[i];
    p.vx[i] += kick * p.ax[i] + c * p.surface_fx[i], p.vy[i] += kick * p.ay[i] + c * p.surface_fy[i];
    p.vz[i] += kick * p.az[i] + c * p.surface_fz[i];
    p.x[i] += dt * p.vx[i], p.y[i] += dt * p.vy[i], p.z[i] += dt * p.vz[i];
  };
  if (extra != 0.0) {
    if (domain.on)
      cosim::parallel_for("sph.kick_drift", move_list.size(), [&](std::size_t k) { kick_held_drift(move_list[k]); });
    else
      cosim::parallel_for("sph.kick_drift", p.n_real, kick_held_drift);
  } else if (domain.on) {
    cosim::parallel_for("sph.kick_drift", move_list.size(), [&](std::size_t k) { kick_drift(move_list[k]); });
  } else {
    cosim::parallel_for("sph.kick_drift", p.n_real, kick_drift);
  }
}

void hold_surface_force(Particles& p, const ActiveDomain& domain) {
  auto add = [&](std::size_t i) {
    const double inv_m = 1.0 / p.mass[i];
    p.ax[i] += p.surface_fx[i] * inv_m, p.ay[i] += p.surface_fy[i] * inv_m, p.az[i] += p.surface_fz[i] * inv_m;
  };
  if (domain.on)
    for (std::uint32_t i : domain.move_list) add(i);
  else
    for (std::size_t i = 0; i < p.n_real; ++i) add(i);
}

}  // namespace snow_sph
