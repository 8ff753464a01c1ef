// The terrain's side of the exchange with a coupled surface (a tyre's tread):
// its contact into the particles and the loads back (surface_contact.hpp),
// the force held over the next window, and the impulse committed per window.
#include <algorithm>

#include "cosim/error.hpp"
#include "snow_sph/placement.hpp"
#include "snow_sph/solver.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {

void Solver::couple(const SurfaceContactParameters& parameters) {
  surface_.coupled = true;
  surface_.params = parameters;
  // Water between a facet and a wall (the floor under a tread) in a film
  // thinner than half a particle drains out of the flow (docs/water.md,
  // "Films thinner than a particle"): half of such a particle no longer fits.
  surface_.params.walls.clear();
  for (const MirrorPlane& plane : m_.planes)
    if (!plane.symmetry) surface_.params.walls.push_back({plane.axis, plane.position, plane.inside_sign});
  surface_.params.drain_film_m = parameters.particle_radius_m;
}

double Solver::surface_contact_limit_dt() const {
  if (!surface_.coupled) return 0.0;
  return surface_stability_limit_dt(m_, surface_.params.stiffness_N_per_m);
}

// Exchange 0, with the particles at t_0 before the first step: a terrain
// placed around the surface's owner loses the particles inside it, and the
// window must be one over which the owner can hold the loads.
void Solver::first_exchange(const ContactSurface& surface, double dt) {
  if (surface_.place_around_owner) {
    // The terrain placed around the body at rest (placement.hpp): what it
    // occupies, and the particles that would overlap it, are not terrain; the
    // state at t_0 is that of the particles left.
    const Particles& p = m_.particles;
    const auto inside = particles_in_body(surface, p.n_real, p.x.data(), p.y.data(), p.z.data(),
                                          surface_.params.particle_radius_m);
    if (!inside.empty()) {
      removed_.displaced_mass_kg += remove_particles(inside).first;
      removed_.displaced_particles += inside.size();
      prepare();
    }
  }
  // Multi-rate: the owner holds these loads over the window (docs/coupling.md).
  surface_.held_load_limit_dt = held_load_window_limit(surface, surface_.params.stiffness_N_per_m, m_.settings.spacing);
  if (dt > surface_.held_load_limit_dt)
    throw cosim::Error("the coupling window " + cosim::number_text(dt) + " s is above the limit " +
                       cosim::number_text(surface_.held_load_limit_dt) + " s for holding the contact loads on the "
                       "surface's lightest node per area (docs/coupling.md); use coupling.scheme: COMMON_STEP "
                       "or a softer coupling.contact_stiffness_scale");
}

void Solver::contact_surface(const ContactSurface* surface, std::uint64_t exchange) {
  surface_.last_surface = surface;
  if (!surface) return;
  // Exchange 0 is made with the particles at t_0, before the first step.
  // The contact's step is the window over which its force is held.
  const double dt = exchange == 0 ? stable_dt() : clock_.window_dt;
  if (exchange == 0) first_exchange(*surface, dt);
  // The owner sent this surface after completing the window of the last
  // exchange, whose loads the window's kicks gave the particles: that window counts.
  if (exchange > 0)
    for (int c = 0; c < 3; ++c) surface_.impulse[c] += surface_.window_kick * surface_.force[c];
  surface_.window_kick = 0.0;
  Particles& p = m_.particles;
  const std::size_t n = p.n_real;
  std::vector<double>& a0 = surface_.a_before;
  a0.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) a0[3 * i] = p.ax[i], a0[3 * i + 1] = p.ay[i], a0[3 * i + 2] = p.az[i];
  surface_.drainable.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    surface_.drainable[i] = m_.materials[p.material[i]].kind == MaterialModel::Kind::water ? 1 : 0;
  surface_contact(*surface, surface_.params, n, p.x.data(), p.y.data(), p.z.data(), p.vx.data(), p.vy.data(),
                  p.vz.data(), p.mass.data(), dt, p.ax.data(), p.ay.data(), p.az.data(), surface_.loads,
                  &surface_.friction_history, p.id.data(), surface_.drainable.data());
  // The force of the surface on each particle, held over the next window (its
  // sub-steps and the work it does in their kicks), and its total (momentum
  // exchanged with the owner).
  double fx = 0.0, fy = 0.0, fz = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dfx = p.mass[i] * (p.ax[i] - a0[3 * i]), dfy = p.mass[i] * (p.ay[i] - a0[3 * i + 1]),
                 dfz = p.mass[i] * (p.az[i] - a0[3 * i + 2]);
    p.surface_fx[i] = dfx, p.surface_fy[i] = dfy, p.surface_fz[i] = dfz;
    fx += dfx, fy += dfy, fz += dfz;
  }
  surface_.force[0] = fx, surface_.force[1] = fy, surface_.force[2] = fz;
  surface_.held = true;
  // What the contact dissipates over the window it is held (its dt) and holds in its springs.
  energy_.surface_friction += surface_.loads.friction_dissipation_J;
  energy_.surface_damping += surface_.loads.damping_dissipation_J;
  energy_.surface_contact_elastic = surface_.loads.elastic_energy_J;
  if (!surface_.loads.drained.empty()) drain(surface_.loads.drained);
  // Where the owner's next surface must reach down to: the particles' reach over the next window.
  const double next_window = m_.settings.coupling_window_s > 0.0 ? m_.settings.coupling_window_s : dt;
  surface_.loads.particle_reach_z_m = particle_reach_z(p.n_real, p.z.data(), p.vz.data(), p.az.data(), next_window,
                                                       surface_.params.particle_radius_m);
}

}  // namespace snow_sph
