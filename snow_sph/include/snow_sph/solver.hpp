#pragma once
// Explicit central-difference time stepping of the SPH terrain: the Solver
// holds the explicit state of the step (step_state.hpp) and runs its stages
// (stages.hpp) in order. A coupled window reads
//   advance_to_exchange()  the window's sub-steps, each kick -> drift ->
//                          boundaries/ghosts/neighbours -> pair rates -> stress
//                          update -> pair forces -> walls, bodies; the last up to
//                          the particle forces at the window's end
//   contact_surface()      the exchange: the owner's surface of that time in,
//                          its contact into the particles' accelerations, loads out
//   finish_window()        the last sub-step's end: energy balance, water
//                          leaving the flow, active domain
// and step() is advance_to_exchange() + finish_window() for a terrain on its own
// (docs/coupling.md, the participant's step; docs/sph.md, "The step as stages").
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cosim/checkpoint.hpp"
#include "snow_sph/model.hpp"
#include "snow_sph/step_state.hpp"
#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

// The coupled surface's side of the terrain: its contact parameters, the
// loads of the last exchange and the force held on the particles until the next.
struct SurfaceCoupling {
  bool coupled = false;
  SurfaceContactParameters params;
  SurfaceContactResult loads;
  FrictionHistory friction_history;  // elastic sticks, keyed by the stable particle id
  std::vector<double> a_before;      // accelerations before the surface contact (scratch)
  std::vector<std::uint8_t> drainable;  // per real particle: 1 for water
  bool held = false;  // Particles::surface_f* hold an exchange's force
  double held_load_limit_dt = 0.0;
  const ContactSurface* last_surface = nullptr;
  double force[3] = {0, 0, 0};    // on the particles, last exchange
  double impulse[3] = {0, 0, 0};  // committed windows
  double window_kick = 0.0;       // the surface force's kicks since the last exchange [s]
  bool place_around_owner = false;
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
  // run makes between advance_to_exchange() and finish_window() (and once
  // before initialise()).
  void couple(const SurfaceContactParameters& parameters);
  // The stable step of the penalty contact with a coupled surface (0: not coupled).
  double surface_contact_limit_dt() const;
  const SurfaceContactResult& surface_loads() const { return surface_.loads; }
  // Exchange n (n = 0 before initialise(), else after the n-th
  // advance_to_exchange()): the contact of the surface at t_n with the
  // particles at t_n, into their accelerations and surface_loads(); null: the
  // surface's owner ended the run.
  void contact_surface(const ContactSurface* surface, std::uint64_t exchange);
  // Impulse of the coupled surface on the particles [N s], over the exchanges
  // whose window the surface's owner completed (it sent the next surface).
  const double* surface_impulse_Ns() const { return surface_.impulse; }

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
  double held_load_limit_dt() const { return surface_.held_load_limit_dt; }
  std::size_t active_particles() const { return domain_.force_list.size(); }
  double mean_active_share() const {
    return domain_.active_samples ? domain_.active_share_sum / domain_.active_samples : 1.0;
  }
  // Water particles drained so far from films thinner than they resolve, and their mass.
  std::size_t drained_particles() const { return removed_.drained_particles; }
  double drained_mass_kg() const { return removed_.drained_mass_kg; }
  // A terrain placed around the surface's owner (coupling.place_terrain_around_loaded_tyre):
  // exchange 0 removes the particles inside it (placement.hpp); how many, and their mass.
  // Call before the first exchange.
  void place_around_surface_owner(bool on) { surface_.place_around_owner = on; }
  std::size_t displaced_particles() const { return removed_.displaced_particles; }
  double displaced_mass_kg() const { return removed_.displaced_mass_kg; }
  // Sets the clock, before the first step: a coupled terrain starts at the
  // time of the owner's first surface (a tyre joins after its loading).
  void start_clock_at(double time_s);
  // Among them, those removed because their density left the valid range.
  std::size_t density_out_particles() const { return removed_.density_out_particles; }

  // Computes the initial stress state, sound speeds and accelerations, so that
  // stability_limit_dt() is that of the first step (a coupled terrain proposes
  // its step from it); initialise() calls it if it was not called.
  void prepare();
  // Starts the energy balance (and the active domain, from the surface of
  // exchange 0); call once before the first step.
  void initialise();

  // The step, in two parts around the exchange with a coupled surface:
  // before_exchange -> exchange -> after_exchange is
  // advance_to_exchange() -> contact_surface() -> finish_window().
  //
  // advance_to_exchange(): one window of the stable step (or the fixed step),
  // up to the particle forces of its end time, without the coupled surface.
  // Coupled, the fixed step is the coupling window, and the terrain sub-steps
  // inside it when its own stable limit falls below it (docs/coupling.md, "The
  // terrain sub-steps"): k equal steps at the CFL factor, the surface's force of
  // the last exchange held on the particles over all of them and kicked with
  // each sub-step's length, so that its impulse over the window is exactly the
  // window times the force, as the surface's owner books it. The sub-steps
  // before the last are whole (finished here); the last stops at the exchange.
  StepStats advance_to_exchange();
  // After the exchange (the coupled surface's contact): the end of the
  // window's last sub-step: energy balance, water leaving the flow, active domain.
  void finish_window();
  // advance_to_exchange() + finish_window(): one step of a terrain on its own.
  StepStats step();

  double time() const { return clock_.time; }
  std::uint64_t steps() const { return clock_.steps; }
  double stable_dt() const;             // with the CFL factor
  double stability_limit_dt() const;    // Courant number 1: a fixed step above it is refused
  std::string limit_cause() const;      // what sets stability_limit_dt(), for messages
  double smallest_limit_dt() const { return smallest_limit_dt_; }  // over the steps taken
  // Coupled: windows the terrain sub-stepped, and the most sub-steps in one.
  std::uint64_t substepped_windows() const { return clock_.substepped_windows; }
  std::uint32_t most_substeps() const { return clock_.most_substeps; }
  // Sub-steps allowed in one window before the run stops with the limit's cause.
  static constexpr std::uint32_t kMaxSubsteps = 1000;
  const EnergyBalance& energy() const { return energy_; }
  const NeighbourList& neighbours() const { return neighbours_.list; }
  std::uint64_t interactions() const { return clock_.interactions; }
  std::size_t rebuilds() const { return neighbours_.rebuilds; }
  bool finite() const;  // no NaN/Inf in the particle state

  // The whole state of the particles, the rigid bodies and the solver after a
  // completed step, and back into a solver built from the same scene (after
  // initialise()): the run goes on as if never stopped (solver_checkpoint.cpp).
  void save(cosim::CheckpointWriter& out) const;
  void restore(const cosim::CheckpointReader& in);

  // Shepard-interpolated pressure at a point (real and ghost particles).
  double pressure_at(double x, double y, double z) const;

 private:
  // One central-difference step of length dt up to the forces of the new time:
  // the stage list of the SPH step (solver.cpp).
  StepStats advance_by(double dt);
  // The end of one step (or sub-step) of length clock_.step_dt.
  void finish_step();
  // Exchange 0's placement around the surface's owner and its window check.
  void first_exchange(const ContactSurface& surface, double dt);
  // Returns true if the neighbour list was rebuilt.
  bool rebuild_if_needed(bool force);
  // The per-particle work arrays, sized for n_real real and n_all particles.
  void size_work_arrays(std::size_t n_real, std::size_t n_all);
  void drain(const std::vector<std::uint32_t>& drained);
  // Takes the particles (ascending indices) out of the terrain; returns their mass and kinetic energy.
  std::pair<double, double> remove_particles(const std::vector<std::uint32_t>& gone);

  // Checkpoint parts (solver_checkpoint.cpp).
  void save_sticks(cosim::CheckpointWriter& out) const;
  void restore_sticks(const cosim::CheckpointReader& in);
  void restore_neighbours(const cosim::CheckpointReader& in, std::size_t n_real, std::size_t size);

  Model& m_;
  NeighbourState neighbours_;
  MaterialFlags flags_;
  PairRates rates_;
  SymmetricField artificial_stress_;  // Gray et al. (2001) R, per particle and ghost
  SymmetricField stress_over_rho2_;   // sigma / rho^2, per particle and ghost
  StepPowers powers_;
  BodyContactWork body_contact_;
  ActiveDomain domain_;
  EnergyBalance energy_;
  StepClock clock_;
  mutable double smallest_limit_dt_ = 1e30;  // stable_dt() keeps the smallest limit it saw
  SurfaceCoupling surface_;
  RemovedParticles removed_;
  bool prepared_ = false;
};

}  // namespace snow_sph
