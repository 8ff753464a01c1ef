// Stability limit: the explicit step's Courant and acceleration limits per
// particle, and the penalty contacts' (omega dt < 2 for central differences).
#include <algorithm>
#include <cmath>

#include "cosim/error.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {
namespace {

// One particle's stable step: h / (c + |v|) (Courant) and sqrt(h / |a|), and
// which of the two is the smaller.
struct ParticleLimit {
  double dt = 1e30, speed = 0.0, acceleration = 0.0;
  bool by_acceleration = false;
};
ParticleLimit particle_limit(const Particles& p, std::size_t i, double h) {
  ParticleLimit l;
  l.speed = std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
  l.dt = h / (p.sound_speed[i] + l.speed);
  l.acceleration = std::sqrt(p.ax[i] * p.ax[i] + p.ay[i] * p.ay[i] + p.az[i] * p.az[i]);
  if (l.acceleration > 0 && std::sqrt(h / l.acceleration) < l.dt)
    l.dt = std::sqrt(h / l.acceleration), l.by_acceleration = true;
  return l;
}

}  // namespace

double particle_stability_limit_dt(const Model& m) {
  const Particles& p = m.particles;
  const double h = m.kernel.h;
  double limit = 1e30;
  // Particles outside the active domain are not integrated: they rest, and their
  // accelerations are those of their last active step (a splash resting against a
  // side wall, whose acceleration the wall's push piled up to 1.3e9 m/s^2 before
  // wall_repulsion skipped resting particles, held a hydroplaning run at 20 sub-steps).
  for (std::size_t i = 0; i < p.n_real; ++i)
    if (p.active[i]) limit = std::min(limit, particle_limit(p, i, h).dt);
  if (!m.bodies.empty() && m.settings.contact_stiffness > 0) {
    double m_min = 1e30;
    for (std::size_t i = 0; i < p.n_real; ++i) m_min = std::min(m_min, p.mass[i]);
    // Penalty spring: omega dt < 2 is the central-difference limit.
    limit = std::min(limit, 2.0 * std::sqrt(m_min / m.settings.contact_stiffness));
  }
  return limit;
}

std::string stability_limit_cause(const Model& m) {
  // The particle that sets the limit, and by which criterion.
  const Particles& p = m.particles;
  const double h = m.kernel.h;
  double limit = 1e30;
  std::size_t worst = p.n_real;
  ParticleLimit worst_limit;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    if (!p.active[i]) continue;  // as particle_stability_limit_dt()
    const ParticleLimit l = particle_limit(p, i, h);
    if (l.dt < limit) limit = l.dt, worst = i, worst_limit = l;
  }
  if (worst == p.n_real) return "contact penalty";
  // Its density and pressure too: a water particle whose density was driven
  // through zero shows a sound speed above c0 (c0 rho0 / |rho| for s = 0).
  const std::string where = "particle " + std::to_string(p.id[worst]) + " at (" + cosim::number_text(p.x[worst]) +
                            ", " + cosim::number_text(p.y[worst]) + ", " + cosim::number_text(p.z[worst]) +
                            ") m, density " + cosim::number_text(p.density[worst]) + " kg/m^3, pressure " +
                            cosim::number_text(p.pressure[worst]) + " Pa";
  if (worst_limit.by_acceleration)
    return "acceleration " + cosim::number_text(worst_limit.acceleration) + " m/s^2 of " + where;
  return "sound speed " + cosim::number_text(p.sound_speed[worst]) + " m/s + speed " +
         cosim::number_text(worst_limit.speed) + " m/s of " + where;
}

double surface_stability_limit_dt(const Model& m, double stiffness_N_per_m) {
  const Particles& p = m.particles;
  double m_min = 1e30;
  for (std::size_t i = 0; i < p.n_real; ++i) m_min = std::min(m_min, p.mass[i]);
  return surface_contact_stable_dt(m_min, stiffness_N_per_m);
}

}  // namespace snow_sph
