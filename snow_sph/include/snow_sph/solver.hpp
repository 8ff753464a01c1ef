#pragma once
// Explicit central-difference time stepping of the SPH terrain. One step is a
// list of stages over explicit state:
//   advance():        kick (v^{n+1/2}) -> drift (x^{n+1}) -> walls/ghosts/neighbours ->
//                     rates (velocity gradient, continuity) -> material update
//                     (sigma^{n+1}) -> forces (a^{n+1}) -> rigid-body contact
//   [coupled: the run's exchange stage: surface of t_{n+1} in ->
//    contact_surface() -> loads out]
//   complete_step():  energy balance -> active domain.
// step() is advance() + complete_step() for a terrain on its own.
// Solid SPH after Libersky et al. (1993) and Gray, Monaghan & Swift (2001);
// weakly compressible water after Monaghan (1994) with delta-SPH density
// diffusion (Molteni & Colagrossi 2009, hydrostatic part removed as in
// Fourtakas et al. 2019).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cosim/checkpoint.hpp"
#include "snow_sph/model.hpp"
#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

// Energies of the simulated particles and bodies [J]; see docs/sph.md.
struct EnergyBalance {
  double kinetic = 0.0;            // particles and rigid bodies
  double internal = 0.0;           // integrated stress power: elastic + plastic (+ water compression)
  double elastic = 0.0;            // current stored elastic energy (from the state)
  double plastic_dissipation = 0.0;
  double viscous_dissipation = 0.0;  // artificial and physical viscosity
  double contact_dissipation = 0.0;  // friction and contact damping
  double contact_elastic = 0.0;      // stored in penalty springs
  double external_work = 0.0;        // gravity, applied loads, prescribed motions,
                                     // the coupled surface, the resting (inactive) terrain
  // Kinetic energy of particles that left the active domain (set at rest there).
  double deactivated_kinetic = 0.0;
  // Kinetic energy of water particles drained from a film they cannot resolve
  // (surface_contact.hpp, SurfaceContactParameters::drain_film_m).
  double drained_kinetic = 0.0;
  double initial_total = 0.0;
  // Abaqus-style balance: KE + IE + VD + FD + contact - W, relative to the
  // largest of KE, IE, W.
  double total() const {
    return kinetic + internal + viscous_dissipation + contact_dissipation + contact_elastic +
           deactivated_kinetic + drained_kinetic - external_work;
  }
  double relative_error() const;
};

struct StepStats {
  double dt = 0.0;            // the step; coupled: the coupling window
  std::size_t clamped = 0;
  bool rebuilt = false;
  std::uint32_t substeps = 1;  // coupled: steps taken inside the window
};

class Solver {
 public:
  explicit Solver(Model& model);

  // Couples the particles to an external surface (call before initialise()):
  // its contact is computed by contact_surface() at every exchange, which the
  // run makes between advance() and complete_step() (and once before initialise()).
  void couple(const SurfaceContactParameters& parameters);
  // The stable step of the penalty contact with a coupled surface (0: not coupled).
  double surface_contact_limit_dt() const;
  const SurfaceContactResult& surface_loads() const { return surface_loads_; }
  // Exchange n (n = 0 before initialise(), else after the n-th advance()): the
  // contact of the surface at t_n with the particles at t_n, into their
  // accelerations and surface_loads(); null: the surface's owner ended the run.
  void contact_surface(const ContactSurface* surface, std::uint64_t exchange);
  // Impulse of the coupled surface on the particles [N s], over the exchanges
  // whose window the surface's owner completed (it sent the next surface).
  const double* surface_impulse_Ns() const { return surface_impulse_; }

  // Active terrain domain (as Chrono's CRM "active domains"; docs/coupling.md):
  // with a coupled surface and margin_m > 0, only particles within margin_m, in
  // plan (x, y; at every depth), of the box around the surface sent (the tyre
  // below its contact band), or still faster than wake_speed, are integrated. The others keep their state
  // (stress, density, hardening) at rest and act on active neighbours as a
  // resting boundary, whose work is booked as external work. A particle that
  // comes into the domain has its forces computed for one step before it moves.
  // wake_limit_m > 0 (at least margin_m): a moving particle farther than this,
  // in plan, from the surface's box is set at rest all the same (its kinetic
  // energy booked as for any particle leaving the domain).
  // Call before initialise().
  void set_active_domain(double margin_m, double wake_speed_m_per_s, double wake_limit_m = 0.0);
  // The largest window over which the surface's owner may hold the loads (exchange 0).
  double held_load_limit_dt() const { return held_load_limit_dt_; }
  std::size_t active_particles() const { return force_list_.size(); }
  double mean_active_share() const { return active_samples_ ? active_share_sum_ / active_samples_ : 1.0; }
  // Water particles drained so far from films thinner than they resolve, and their mass.
  std::size_t drained_particles() const { return drained_particles_; }
  double drained_mass_kg() const { return drained_mass_kg_; }
  // A terrain placed around the surface's owner (coupling.place_terrain_around_loaded_tyre):
  // exchange 0 removes the particles inside it (placement.hpp); how many, and their mass.
  // Call before the first exchange.
  void place_around_surface_owner(bool on) { place_around_owner_ = on; }
  std::size_t displaced_particles() const { return displaced_particles_; }
  double displaced_mass_kg() const { return displaced_mass_kg_; }
  // Sets the clock, before the first step: a coupled terrain starts at the
  // time of the owner's first surface (a tyre joins after its loading).
  void start_clock_at(double time_s);
  // Among them, those removed because their density left the valid range.
  std::size_t density_out_particles() const { return density_out_particles_; }

  // Computes the initial stress state, sound speeds and accelerations, so that
  // stability_limit_dt() is that of the first step (a coupled terrain proposes
  // its step from it); initialise() calls it if it was not called.
  void prepare();
  // Starts the energy balance (and the active domain, from the surface of
  // exchange 0); call once before the first step.
  void initialise();
  // The stages of one step of size stable_dt() (or the fixed step) up to the
  // particle forces of the new time, without the coupled surface ...
  // Coupled, the fixed step is the coupling window, and the terrain sub-steps
  // inside it when its own stable limit falls below it (docs/coupling.md, "The
  // terrain sub-steps"): k equal steps at the CFL factor, the surface's force of
  // the last exchange held on the particles over all of them and kicked with
  // each sub-step's length, so that its impulse over the window is exactly the
  // window times the force, as the surface's owner books it.
  StepStats advance();
  // ... and its end, after the coupled surface's contact: energies, active domain.
  void complete_step();
  // advance() + complete_step(): one step of a terrain on its own.
  StepStats step();

  double time() const { return time_; }
  std::uint64_t steps() const { return steps_; }
  double stable_dt() const;             // with the CFL factor
  double stability_limit_dt() const;    // Courant number 1: a fixed step above it is refused
  std::string limit_cause() const;      // what sets stability_limit_dt(), for messages
  double smallest_limit_dt() const { return smallest_limit_dt_; }  // over the steps taken
  // Coupled: windows the terrain sub-stepped, and the most sub-steps in one.
  std::uint64_t substepped_windows() const { return substepped_windows_; }
  std::uint32_t most_substeps() const { return most_substeps_; }
  // Sub-steps allowed in one window before the run stops with the limit's cause.
  static constexpr std::uint32_t kMaxSubsteps = 1000;
  const EnergyBalance& energy() const { return energy_; }
  const NeighbourList& neighbours() const { return list_; }
  std::uint64_t interactions() const { return interactions_; }
  std::size_t rebuilds() const { return rebuilds_; }
  bool finite() const;  // no NaN/Inf in the particle state

  // The whole state of the particles, the rigid bodies and the solver after a
  // completed step, and back into a solver built from the same scene (after
  // initialise()): the run goes on as if never stopped (solver_checkpoint.cpp).
  void save(cosim::CheckpointWriter& out) const;
  void restore(const cosim::CheckpointReader& in);

  // Shepard-interpolated pressure at a point (real and ghost particles).
  double pressure_at(double x, double y, double z) const;

 private:
  // One central-difference step of length dt up to the forces of the new time.
  StepStats advance_by(double dt);
  // Adds the held surface force to the accelerations after a sub-step's force pass.
  void hold_surface_force();
  void rebuild_if_needed(bool force);
  void compute_rates();
  // Correct: the corrected velocity gradient (gradient_correction.hpp); a template
  // argument so that the plain loop carries none of its sums.
  template <KernelType T, bool Correct> void compute_rates_t();
  template <KernelType T> void compute_forces_t();
  void update_materials(double dt);
  void compute_forces();
  void compute_contact(double dt);
  void update_energy(double dt);
  // Active domain: which particles are computed and moved next step.
  void update_activity(const ContactSurface* surface);
  void rebuild_lists();
  void drain(const std::vector<std::uint32_t>& drained);
  // Takes the particles (ascending indices) out of the terrain; returns their mass and kinetic energy.
  std::pair<double, double> remove_particles(const std::vector<std::uint32_t>& gone);
  template <class Body> void for_active(const char* label, Body&& body);

  Model& m_;
  NeighbourList list_;
  std::vector<double> ref_x_, ref_y_, ref_z_;
  // Per-particle work arrays: velocity gradient and artificial stress.
  std::vector<double> lxx_, lxy_, lxz_, lyx_, lyy_, lyz_, lzx_, lzy_, lzz_;
  std::vector<float> pair_f_, pair_inv_;  // per listed pair: F = (1/r) dW/dr, 1/(r^2+0.01h^2)
  std::vector<double> qxx_, qyy_, qzz_, qxy_, qyz_, qxz_;  // sigma / rho^2
  std::vector<double> rxx_, ryy_, rzz_, rxy_, ryz_, rxz_;
  // Per particle, ghosts included: 1 for water, else 0; water's viscosity, else 0.
  std::vector<double> is_water_, water_viscosity_;
  std::vector<double> stress_power_, viscous_power_, contact_fx_, contact_fy_, contact_fz_;
  std::vector<double> contact_dissipation_, wall_power_;
  std::vector<double> plastic_increment_;
  double time_ = 0.0, dt_prev_ = 0.0, w_dx_ = 1.0;
  std::uint64_t steps_ = 0, interactions_ = 0;
  std::size_t rebuilds_ = 0;
  bool any_artificial_stress_ = false;
  bool any_water_ = false;
  EnergyBalance energy_;
  bool coupled_ = false;
  double step_dt_ = 0.0;  // the step advance() took (complete_step() and the contact use it)
  SurfaceContactParameters surface_params_;
  SurfaceContactResult surface_loads_;
  FrictionHistory friction_history_;  // elastic sticks, keyed by the stable particle id
  // Accelerations before the surface contact (scratch of contact_surface()).
  std::vector<double> a_before_;
  bool surface_held_ = false;  // Particles::surface_f* hold an exchange's force
  bool prepared_ = false;
  mutable double smallest_limit_dt_ = 1e30;
  double held_load_limit_dt_ = 0.0;
  const ContactSurface* last_surface_ = nullptr;
  double surface_force_[3] = {0, 0, 0};    // on the particles, last exchange
  double surface_impulse_[3] = {0, 0, 0};  // committed windows
  double window_surface_kick_ = 0.0;       // the surface force's kicks since the last exchange [s]
  std::vector<std::uint8_t> drainable_;   // per real particle: 1 for water
  std::size_t drained_particles_ = 0;
  double drained_mass_kg_ = 0.0;
  std::size_t density_out_particles_ = 0;
  bool place_around_owner_ = false;
  std::size_t displaced_particles_ = 0;
  double displaced_mass_kg_ = 0.0;
  double window_dt_ = 0.0;                 // the last window advance() took
  std::uint64_t substepped_windows_ = 0;
  std::uint32_t most_substeps_ = 1;
  // Active domain.
  double active_margin_m_ = 0.0, wake_speed_ = 0.0, wake_limit_m_ = 0.0;
  bool domain_ = false;
  std::vector<std::uint32_t> force_list_, move_list_;
  std::vector<double> frozen_;          // per particle and ghost: 1 at rest outside the domain
  std::vector<double> boundary_power_;  // work rate of resting neighbours on an active particle
  double active_share_sum_ = 0.0;
  std::uint64_t active_samples_ = 0;
};

}  // namespace snow_sph
