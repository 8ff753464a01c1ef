#pragma once
// The explicit state of one SPH step, grouped by the stage that fills it
// (stages.hpp): the neighbour list and the ghosts' material flags (refreshed
// before the pair loops), the pair rates, the stresses the force pass reads,
// the per-particle powers of the energy balance, the active domain, the clock.
// Each stage reads what earlier stages wrote and writes only its own group,
// so the seams between them are where a halo exchange (ghost and remote
// particles refreshed before the pair loops) and other pair-loop precisions go.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "cosim/parallel.hpp"
#include "snow_sph/neighbours.hpp"
#include "snow_sph/particles.hpp"

namespace snow_sph {

// Energies of the simulated particles and bodies [J]; see docs/sph.md,
// "Energy balance". The lumped terms of the balance (total()) and, beside
// them, their parts: each a power summed per step like the lumped one.
struct EnergyBalance {
  double kinetic = 0.0;            // particles and rigid bodies
  double internal = 0.0;           // integrated stress power: elastic + plastic (+ water compression)
  double elastic = 0.0;            // current stored elastic energy (from the state)
  double plastic_dissipation = 0.0;  // = plastic_cap + plastic_shear
  double viscous_dissipation = 0.0;  // = artificial_viscous + damping + water_viscous
  double contact_dissipation = 0.0;  // the rigid bodies' contact: friction and damping
  double ground_friction_dissipation = 0.0;  // the container walls' Coulomb friction (ground_friction.cpp)
  double contact_elastic = 0.0;      // stored in the rigid bodies' penalty springs
  double external_work = 0.0;        // = gravity + walls + bodies + resting terrain + surface on particles
  // Kinetic energy of particles that left the active domain (set at rest there).
  double deactivated_kinetic = 0.0;
  // Kinetic energy of water particles drained from a film they cannot resolve
  // (surface_contact.hpp, SurfaceContactParameters::drain_film_m).
  double drained_kinetic = 0.0;
  double initial_total = 0.0;
  double initial_kinetic = 0.0;  // kinetic at the start (kinetic - initial_kinetic: what the run left moving)

  // The parts. Plastic work on the cap (mdpc surface 2) and on the shear side
  // (Drucker-Prager line, transition and tension apex: surfaces 1, 3, 4).
  double plastic_cap = 0.0, plastic_shear = 0.0;
  // Monaghan's (1992) artificial viscosity Pi_ij; the quasi-static damping
  // (Settings::damping_per_s); water's physical viscosity (Morris et al. 1997).
  double artificial_viscous = 0.0, damping = 0.0, water_viscous = 0.0;
  // The external work by source: gravity, the walls' repulsion, the rigid
  // bodies' loads and prescribed motion, the resting (inactive) terrain, and
  // the coupled surface's force on the particles (at the particles' velocity).
  double gravity_work = 0.0, wall_work = 0.0, body_work = 0.0, resting_terrain_work = 0.0;
  double surface_work_on_particles = 0.0;
  // The particle-facet contact with the coupled surface (surface_contact.hpp):
  // what its friction and damping dissipated between the surface and the
  // particles, and what its penalty springs hold now. The surface did this
  // work on top of surface_work_on_particles (outside total(): it enters the
  // work done and the dissipation alike).
  double surface_friction = 0.0, surface_damping = 0.0, surface_contact_elastic = 0.0;
  double initial_surface_contact_elastic = 0.0;  // at t_0 (a tyre placed in the snow already presses on it)

  // Abaqus-style balance: KE + IE + VD + FD + contact - W, relative to the
  // largest of KE, IE, W.
  double total() const {
    return kinetic + internal + viscous_dissipation + contact_dissipation + contact_elastic + deactivated_kinetic +
           drained_kinetic + ground_friction_dissipation - external_work;
  }
  double relative_error() const;
  // The work done on the terrain by the coupled surface, at the surface: on the
  // particles plus what the contact dissipated and holds in its springs.
  double coupled_surface_work() const {
    return surface_work_on_particles + surface_friction + surface_damping + surface_contact_elastic -
           initial_surface_contact_elastic;
  }
  // All the work done on the terrain: the external work less the surface's
  // part on the particles, plus its part at the surface.
  double work_on_terrain() const { return external_work - surface_work_on_particles + coupled_surface_work(); }
};

// The neighbour list (cell list -> CSR, neighbours.hpp) with the positions it
// was built at: it is rebuilt when a particle has moved half the skin.
struct NeighbourState {
  NeighbourList list;
  std::vector<double> ref_x, ref_y, ref_z;
  std::size_t rebuilds = 0;
};

// Per particle, ghosts included (made anew with the ghosts): 1 for water, else
// 0; water's viscosity, else 0. And what the scene's materials switch on.
struct MaterialFlags {
  std::vector<double> is_water, water_viscosity;
  bool any_water = false;
  bool any_artificial_stress = false;
  double w_dx = 1.0;  // W(dx): the artificial stress's reference kernel value
};

// What the rates pass leaves for the material update and the force pass.
struct PairRates {
  // Per real particle: the velocity gradient L.
  std::vector<double> lxx, lxy, lxz, lyx, lyy, lyz, lzx, lzy, lzz;
  // Per listed pair: F = (1/r) dW/dr and 1/(r^2 + 0.01 h^2) (same positions in both passes).
  std::vector<float> pair_f, pair_inv;
};

// A symmetric tensor per particle, ghosts included.
struct SymmetricField {
  std::vector<double> xx, yy, zz, xy, yz, xz;
  std::vector<std::vector<double>*> all() { return {&xx, &yy, &zz, &xy, &yz, &xz}; }
};

// Per real particle, this step: the powers and increments the energy balance sums.
// viscous is the sum of artificial_viscous, damping and water_viscous;
// plastic_cap_increment is plastic_increment where the cap was the active surface, else 0.
struct StepPowers {
  std::vector<double> stress, viscous, plastic_increment, wall;
  std::vector<double> ground_friction_increment;  // [J] the walls' Coulomb friction (ground_friction.cpp)
  std::vector<double> artificial_viscous, damping, water_viscous, plastic_cap_increment;
  std::vector<std::vector<double>*> all() {
    return {&stress,  &viscous,       &plastic_increment,    &wall, &ground_friction_increment, &artificial_viscous,
            &damping, &water_viscous, &plastic_cap_increment};
  }
};

// Per real particle: a rigid body's contact force and the energy its contact dissipated.
struct BodyContactWork {
  std::vector<double> fx, fy, fz, dissipation;
  std::vector<std::vector<double>*> all() { return {&fx, &fy, &fz, &dissipation}; }
};

// Active terrain domain (as Chrono's CRM "active domains"; docs/coupling.md):
// which particles are computed (force_list) and moved (move_list) this step.
struct ActiveDomain {
  double margin_m = 0.0, wake_speed = 0.0, wake_limit_m = 0.0;
  bool on = false;
  std::vector<std::uint32_t> force_list, move_list;
  std::vector<double> frozen;          // per particle and ghost: 1 at rest outside the domain
  std::vector<double> boundary_power;  // work rate of resting neighbours on an active particle
  double active_share_sum = 0.0;
  std::uint64_t active_samples = 0;
};

// Runs body(i) in parallel over the particles computed this step.
template <class Body>
void for_active(const ActiveDomain& domain, std::size_t n_real, const char* label, Body&& body) {
  if (domain.on)
    cosim::parallel_for(label, domain.force_list.size(), [&](std::size_t k) { body(domain.force_list[k]); });
  else
    cosim::parallel_for(label, n_real, body);
}

// The clock and step counters.
struct StepClock {
  double time = 0.0, dt_prev = 0.0;
  double step_dt = 0.0;    // the step advance_by() took (the step's end and the contact use it)
  double window_dt = 0.0;  // the last window advance_to_exchange() took
  std::uint64_t steps = 0, interactions = 0;
  std::uint64_t substepped_windows = 0;
  std::uint32_t most_substeps = 1;
};

// Particles taken out of the terrain, by cause.
struct RemovedParticles {
  std::size_t drained_particles = 0;
  double drained_mass_kg = 0.0;
  std::size_t density_out_particles = 0;
  std::size_t displaced_particles = 0;
  double displaced_mass_kg = 0.0;
};

}  // namespace snow_sph
