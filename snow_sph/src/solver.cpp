// The SPH terrain's step as a list of stages (stages.hpp) over the Solver's
// explicit state (step_state.hpp), and the particles' setup before the first.
#include "snow_sph/solver.hpp"

#include <cmath>

#include "cosim/error.hpp"
#include "snow_sph/boundaries.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {

Solver::Solver(Model& model) : m_(model) {}

// One central-difference step of length dt, up to the particle forces of the
// new time (a coupled window's exchange point when it is its last sub-step).
StepStats Solver::advance_by(double dt) {
  Particles& p = m_.particles;
  StepStats stats;
  stats.dt = dt;
  clock_.window_dt = dt;
  // Integration: kick v^{n+1/2} (with a held surface force's work) and drift x^{n+1}.
  const KickLengths kick = kick_lengths(clock_.steps, clock_.dt_prev, dt, surface_.held);
  if (surface_.held) {
    const double work = held_surface_work(p, domain_, kick);
    energy_.external_work += work;
    energy_.surface_work_on_particles += work;
    surface_.window_kick += kick.surface;
  }
  kick_drift(p, domain_, kick, dt);
  move_bodies(m_, clock_.time, kick.kick, dt);
  clock_.time += dt;
  // Boundaries: particles back inside the walls; ghosts and neighbour list made
  // current (the halo point: the pair loops below read other particles).
  stats.clamped = clamp_to_walls(m_);
  stats.rebuilt = rebuild_if_needed(false);
  // Pair rates -> stress update -> ghosts' stress (second halo point) -> pair forces.
  compute_pair_rates(m_, neighbours_.list, flags_, domain_, rates_);
  update_stress(m_, domain_, rates_, dt, artificial_stress_, powers_);
  refresh_ghost_state(m_);
  compute_pair_forces(m_, neighbours_.list, flags_, rates_, artificial_stress_, stress_over_rho2_, powers_, domain_);
  // Walls and rigid bodies on the particles.
  wall_repulsion(m_, p.ax.data(), p.ay.data(), p.az.data(), powers_.wall.data());
  body_contact(m_, dt, body_contact_, energy_);
  // Last: it opposes every other force on the particles next to a wall.
  ground_friction(m_, neighbours_.list, rates_, stress_over_rho2_, dt, powers_.ground_friction_increment);
  clock_.step_dt = dt;
  return stats;
}

// The end of a step, after the exchange: energy balance, water leaving the
// flow, active domain for the next step, counters.
void Solver::finish_step() {
  const Particles& p = m_.particles;
  const double dt = clock_.step_dt;
  update_energy(m_, domain_, powers_, clock_.time, dt, energy_);
  if (flags_.any_water) {
    const std::vector<std::uint32_t> spray = water_leaving_flow(m_, removed_.density_out_particles);
    if (!spray.empty()) drain(spray);
  }
  if (domain_.on) {
    for (std::uint32_t i : domain_.force_list) clock_.interactions += p.neighbour_count[i];
    if (surface_.last_surface)  // no surface: the run has ended
      energy_.deactivated_kinetic += update_activity(m_.particles, surface_.last_surface, domain_);
  } else {
    for (std::size_t i = 0; i < p.n_real; ++i) clock_.interactions += p.neighbour_count[i];
  }
  clock_.dt_prev = dt;
  ++clock_.steps;
}

void Solver::prepare() {
  Particles& p = m_.particles;
  prepared_ = true;
  flags_.w_dx = m_.kernel.value(m_.settings.spacing);
  flags_.any_water = false;
  for (const auto& mat : m_.materials)
    flags_.any_water = flags_.any_water || mat.kind == MaterialModel::Kind::water;
  flags_.any_artificial_stress = m_.settings.artificial_stress_epsilon > 0;
  rebuild_if_needed(true);
  size_work_arrays(p.n_real, p.size());
  // The forces of the state at t_0, as a step's stages compute them.
  compute_pair_rates(m_, neighbours_.list, flags_, domain_, rates_);
  update_stress(m_, domain_, rates_, 0.0, artificial_stress_, powers_);
  refresh_ghost_state(m_);
  compute_pair_forces(m_, neighbours_.list, flags_, rates_, artificial_stress_, stress_over_rho2_, powers_, domain_);
  wall_repulsion(m_, p.ax.data(), p.ay.data(), p.az.data(), powers_.wall.data());
  body_contact(m_, 1e-30 + stable_dt(), body_contact_, energy_);
  ground_friction(m_, neighbours_.list, rates_, stress_over_rho2_, stable_dt(), powers_.ground_friction_increment);
}

void Solver::size_work_arrays(std::size_t n_real, std::size_t n_all) {
  for (auto* v : {&rates_.lxx, &rates_.lxy, &rates_.lxz, &rates_.lyx, &rates_.lyy, &rates_.lyz, &rates_.lzx,
                  &rates_.lzy, &rates_.lzz})
    v->assign(n_real, 0.0);
  for (auto* v : powers_.all()) v->assign(n_real, 0.0);
  for (auto* v : body_contact_.all()) v->assign(n_real, 0.0);
  for (auto* v : artificial_stress_.all()) v->assign(n_all, 0.0);
}

void Solver::initialise() {
  if (!prepared_) prepare();
  if (domain_.on) {
    // Every particle's acceleration is that of the state at t_0 (prepare()), so
    // those inside the domain move from the first step.
    energy_.deactivated_kinetic += update_activity(m_.particles, surface_.last_surface, domain_);
    for (std::size_t i = 0; i < m_.particles.n_real; ++i) m_.particles.moving[i] = m_.particles.active[i];
    rebuild_active_lists(m_.particles, domain_);
  }
  // Exchange 0's contact, made before this with the particles at t_0, is the
  // first window's: what it dissipates over that window counts; its springs
  // hold their energy at t_0, the start of the surface's work.
  const EnergyBalance contact_at_start = energy_;
  energy_ = EnergyBalance{};
  energy_.contact_elastic = 0.0;
  energy_.surface_friction = contact_at_start.surface_friction;
  energy_.surface_damping = contact_at_start.surface_damping;
  energy_.surface_contact_elastic = energy_.initial_surface_contact_elastic = contact_at_start.surface_contact_elastic;
  update_energy(m_, domain_, powers_, clock_.time, 0.0, energy_);
  energy_.initial_total = energy_.total();
  energy_.initial_kinetic = energy_.kinetic;
}

bool Solver::rebuild_if_needed(bool force) {
  const bool rebuilt = refresh_ghosts_and_neighbours(m_, neighbours_, flags_, force);
  if (rebuilt && domain_.on) rebuild_active_lists(m_.particles, domain_);  // particles were reordered and ghosts made
  return rebuilt;
}

void Solver::set_active_domain(double margin_m, double wake_speed_m_per_s, double wake_limit_m) {
  domain_.margin_m = margin_m;
  domain_.wake_speed = wake_speed_m_per_s;
  domain_.wake_limit_m = wake_limit_m;
  domain_.on = surface_.coupled && margin_m > 0.0;
}

void Solver::start_clock_at(double time_s) {
  if (clock_.steps != 0) throw cosim::Error("the terrain's clock can be set only before its first step");
  clock_.time = time_s;
}

// Removes the drained particles (ascending indices) from the flow: their mass
// leaves the terrain and their kinetic energy the balance; ghosts and lists are
// made anew for the particles that stay.
void Solver::drain(const std::vector<std::uint32_t>& drained) {
  const auto [mass, kinetic] = remove_particles(drained);
  energy_.drained_kinetic += kinetic;
  removed_.drained_mass_kg += mass;
  removed_.drained_particles += drained.size();
}

std::pair<double, double> Solver::remove_particles(const std::vector<std::uint32_t>& gone) {
  const std::pair<double, double> taken = take_out_particles(m_.particles, gone);
  rebuild_if_needed(true);
  return taken;
}

bool Solver::finite() const {
  const Particles& p = m_.particles;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    if (!std::isfinite(p.x[i] + p.y[i] + p.z[i] + p.vx[i] + p.vy[i] + p.vz[i] + p.density[i] +
                       p.sxx[i] + p.syy[i] + p.szz[i] + p.sxy[i] + p.syz[i] + p.sxz[i]))
      return false;
  }
  for (const auto& b : m_.bodies)
    if (!std::isfinite(b.z + b.vz)) return false;
  return true;
}

double Solver::pressure_at(double x, double y, double z) const {
  const Particles& p = m_.particles;
  const double s2 = m_.kernel.support * m_.kernel.support;
  double num = 0, den = 0;
  for (std::size_t j = 0; j < p.size(); ++j) {
    const double rx = x - p.x[j], ry = y - p.y[j], rz = z - p.z[j];
    const double r2 = rx * rx + ry * ry + rz * rz;
    if (r2 >= s2) continue;
    const double w = m_.kernel.value(std::sqrt(r2)) * p.mass[j] / p.density[j];
    num += w * p.pressure[j];
    den += w;
  }
  return den > 0 ? num / den : 0.0;
}

}  // namespace snow_sph
