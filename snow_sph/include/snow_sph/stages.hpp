#pragma once
// The stages of one SPH step, as free functions over explicit state
// (step_state.hpp); Solver::advance_by (solver.cpp) lists them in order:
//   integration        kick v^{n+1/2}, drift x^{n+1} (particles, rigid bodies)
//   boundaries         clamp to walls; ghosts and neighbour list refreshed
//                      (the halo point: everything the pair loops read is current)
//   pair rates         velocity gradient, continuity (+ delta-SPH)
//   stress update      density, Jaumann rotation, mdpc / equation of state
//   ghost state        ghosts take their sources' new stress (second halo point)
//   pair forces        a^{n+1} from stress, viscosity, artificial stress
//   walls, bodies      wall repulsion; rigid-body contact
//   ground friction    Coulomb friction of the container's COULOMB walls
// and after the exchange (Solver::finish_step): energy balance, water leaving
// the flow, active domain.
// Solid SPH after Libersky et al. (1993) and Gray, Monaghan & Swift (2001);
// weakly compressible water after Monaghan (1994) with delta-SPH density
// diffusion (Molteni & Colagrossi 2009, hydrostatic part removed as in
// Fourtakas et al. 2019).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "snow_sph/model.hpp"
#include "snow_sph/step_state.hpp"
#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

// --- boundaries and ghosts (neighbour_refresh.cpp) ---
// Rebuilds ghosts, particle order and neighbour list when a particle moved
// half the skin (or `force`), else refreshes the ghosts' positions and
// velocities. Returns true if it rebuilt (the particles were reordered).
bool refresh_ghosts_and_neighbours(Model& m, NeighbourState& neighbours, MaterialFlags& flags, bool force);

// --- pair rates (pair_rates.cpp) ---
// Velocity gradient L_i = (1/rho_i) sum_j m_j (v_j - v_i) (x) grad_i W_ij and
// continuity drho_i/dt = -rho_i tr(L_i), plus delta-SPH diffusion for water;
// the pair factors for the force pass.
void compute_pair_rates(Model& m, const NeighbourList& list, const MaterialFlags& flags, const ActiveDomain& domain,
                        PairRates& rates);

// --- stress update (stress_update.cpp) ---
// Density, then stress (mdpc for snow, the equation of state for water), the
// artificial stress and the step's stress power and plastic work.
void update_stress(Model& m, const ActiveDomain& domain, const PairRates& rates, double dt,
                   SymmetricField& artificial_stress, StepPowers& powers);

// --- pair forces (pair_forces.cpp) ---
// Accelerations of the active particles from their neighbours' stress,
// viscosity and artificial stress, and gravity; the viscous power, and the
// power of resting neighbours (ActiveDomain::boundary_power).
void compute_pair_forces(Model& m, const NeighbourList& list, const MaterialFlags& flags, const PairRates& rates,
                         SymmetricField& artificial_stress, SymmetricField& stress_over_rho2, StepPowers& powers,
                         ActiveDomain& domain);

// --- integration (integration.cpp) ---
// The kick of this step: the central difference's, and that of a coupled
// surface's force held over the window (see integration.cpp).
struct KickLengths {
  double kick = 0.0;     // (dt_prev + dt)/2, first step dt/2
  double surface = 0.0;  // the held surface force's kick: dt, first step dt/2
  double extra = 0.0;    // surface - kick when a surface force is held, else 0
};
KickLengths kick_lengths(std::uint64_t steps, double dt_prev, double dt, bool surface_held);
// Work of the held surface forces over this kick (central-difference work).
double held_surface_work(const Particles& p, const ActiveDomain& domain, const KickLengths& kick);
// v^{n+1/2} = v^{n-1/2} + kick a^n (+ the held force's extra kick), x^{n+1} = x^n + dt v^{n+1/2}.
void kick_drift(Particles& p, const ActiveDomain& domain, const KickLengths& kick, double dt);
// Adds the held surface force to the accelerations after a sub-step's force pass.
void hold_surface_force(Particles& p, const ActiveDomain& domain);

// --- rigid bodies (rigid_bodies.cpp) ---
// Kick and drift of the rigid bodies (prescribed or loaded), at time t before the step.
void move_bodies(Model& m, double time_s, double kick, double dt);
// Penalty contact of the particles with the rigid cylinders.
void body_contact(Model& m, double dt, BodyContactWork& work, EnergyBalance& energy);

// --- ground friction (ground_friction.cpp) ---
// Coulomb friction of the container's COULOMB walls on the particles their
// images reach, bounded by mu times the images' push (the pair forces' terms,
// from the list and the stress / rho^2 of the force pass), added to the
// accelerations after every other force of the step; dissipated_J[i] the work
// it takes out of particle i over the next kick (dt). Nothing, and no array
// touched, without a COULOMB wall.
void ground_friction(Model& m, const NeighbourList& list, const PairRates& rates,
                     const SymmetricField& stress_over_rho2, double dt, std::vector<double>& dissipated_J);

// --- active domain (active_domain.cpp) ---
void rebuild_active_lists(const Particles& p, ActiveDomain& domain);
// Which particles are computed and moved next step; returns the kinetic
// energy of those set at rest.
double update_activity(Particles& p, const ContactSurface* surface, ActiveDomain& domain);

// --- energy balance (energy_balance.cpp) ---
void update_energy(const Model& m, const ActiveDomain& domain, const StepPowers& powers, double time_s, double dt,
                   EnergyBalance& energy);

// --- particles leaving the terrain (particle_removal.cpp) ---
// Takes the particles (ascending indices) out; returns their mass and kinetic
// energy. The caller rebuilds ghosts and lists.
std::pair<double, double> take_out_particles(Particles& p, const std::vector<std::uint32_t>& gone);
// Water that leaves the flow at the end of a step: spray above the box, or
// density out of its valid range (counted in density_out).
std::vector<std::uint32_t> water_leaving_flow(const Model& m, std::size_t& density_out);

// --- stability limit (stability.cpp) ---
// The particles' stable step (Courant number 1) and the rigid-body contact's.
double particle_stability_limit_dt(const Model& m);
// What sets particle_stability_limit_dt(), for messages.
std::string stability_limit_cause(const Model& m);
// The penalty contact's stable step with a coupled surface of this stiffness.
double surface_stability_limit_dt(const Model& m, double stiffness_N_per_m);

}  // namespace snow_sph
