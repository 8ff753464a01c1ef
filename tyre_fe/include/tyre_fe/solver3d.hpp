#pragma once
// Explicit central-difference step of the 3D tyre (Belytschko, Liu & Moran 2000,
// box 6.1): lumped mass, one-point hexahedra, follower inflation pressure on the
// inner liner, a rigid rim (reference node at the wheel centre, free in x, z and
// rotation about y, ISO 8855) and a flat rigid road with penalty contact and
// Coulomb friction. A step is a list of stages over explicit state:
//   compute_forces:    element forces -> gather -> pressure -> road contact
//   add_terrain_loads: the terrain's loads held over the coupling window (coupled)
//   integrate:         damping -> rim rigid body -> velocity and position update -> energy.
// A coupled run (tyre_fe/run.cpp) puts its exchange around them at a window's
// start: send surface -> compute_forces -> receive loads -> add_terrain_loads -> integrate,
// so that the terrain works on the surface while the element forces are computed.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tyre_fe/model3d.hpp"
#include "tyre_fe/terrain_port.hpp"

namespace tyre_fe {

// How the rim is driven in the current stage.
struct RimDrive {
  bool hold_x = true;              // x fixed (loading) or at `forward_speed`
  double forward_speed_m_per_s = 0.0;
  bool spin_prescribed = true;     // spin at `angular_velocity` (0: held) ...
  double angular_velocity_rad_per_s = 0.0;
  double drive_torque_Nm = 0.0;    // ... or free with this torque about y
  double wheel_load_N = 0.0;       // downward force on the rim node
  bool hold_z = false;             // z fixed (check at rest after the transfer) ...
  bool prescribe_vz = false;       // ... or moving at this vertical speed (a pushed tread block)
  double vertical_speed_m_per_s = 0.0;
};

struct RimState {
  double x = 0.0, z = 0.0, angle = 0.0;       // rim node position and spin angle
  double vx = 0.0, vz = 0.0, omega = 0.0;
  double mass_kg = 0.0, inertia_kg_m2 = 0.0;  // rim + the tyre nodes it carries
  // Moment about y and force that the tyre exerts on the rim (from the rim
  // nodes), and RM2: the moment the rim applies to the tyre (ISO y).
  double tyre_force_x_N = 0.0, tyre_force_z_N = 0.0, tyre_moment_y_Nm = 0.0;
  double rm2_Nm = 0.0;
  // The drive of the last step: torque about y (0 if the spin is prescribed) and wheel load.
  double applied_torque_Nm = 0.0, wheel_load_N = 0.0;
};

struct RoadState {
  bool present = false;
  double height_m = 0.0;  // road plane z
  double friction_coefficient = 0.0;
  double penalty_scale = 0.1;
  // Per contact node (Model3d::contact_nodes): stick anchor in x, y and contact flag.
  std::vector<double> anchor_x, anchor_y;
  std::vector<char> in_contact;
  std::vector<double> normal_force_N;   // last step
  // Totals of the last step: force of the road on the tyre, area in contact.
  double force_x_N = 0.0, force_y_N = 0.0, force_z_N = 0.0, contact_area_m2 = 0.0;
  double friction_dissipation_J = 0.0;
};

// The tyre's side of a coupling with a terrain solver: its loads replace or join the road.
// Multi-rate (docs/coupling.md): one exchange per coupling window of
// `substeps` tyre steps; the loads of the window's start are held over it.
// The run makes the exchange through its port (terrain_port.hpp).
struct TerrainCoupling {
  ContactSurfaceDef surface;
  std::uint64_t exchange = 0;   // windows exchanged
  int substeps = 1;             // tyre steps per coupling window
  int substep = 0;              // position in the current window (0: its start)
  // Facets with a node below this height (the scene's contact band) or below
  // the particles' reach that the terrain reported with its last loads are sent.
  double band_m = 0.1;
  double highest_band_m = 0.0;  // the highest the sent band reached over the run
  cosim::SurfaceState sent;     // the surface sent at the current window's start
  cosim::SurfaceLoads loads;    // of the current window
  cosim::SurfaceLoadTotals load_totals;
  // Impulse of the terrain's loads on the tyre [N s]: the held loads times each
  // sub-step, over the windows completed and followed by the next exchange
  // (the terrain books the same windows), and over the window under way.
  double impulse_Ns[3] = {0.0, 0.0, 0.0}, window_impulse_Ns[3] = {0.0, 0.0, 0.0};
};

struct Energies {
  double kinetic_J = 0.0;
  double internal_J = 0.0;   // strain + hourglass
  double hourglass_J = 0.0;
  double external_work_J = 0.0;  // pressure, wheel load, torque, prescribed motion
  double damping_work_J = 0.0;   // work of mass damping and bulk viscosity (<= 0)
  double contact_work_J = 0.0;   // work of the road's and the terrain's forces (penalty + friction)
  double initial_J = 0.0;        // E_kin + E_int at the first step (the inflated state)
  // Parts of the above: the inflation pressure's share of external_work_J (the
  // rest is the rim's: wheel load, drive torque, prescribed motion), and the
  // bulk viscosity's share of damping_work_J (the rest is mass damping,
  // including kinetic energy removed by zero_velocities).
  double pressure_work_J = 0.0;
  double bulk_viscous_work_J = 0.0;                            // <= 0
  double initial_internal_J = 0.0, initial_hourglass_J = 0.0;  // at the first step
  // |E_kin + E_int - E_0 - W_ext - W_damp - W_contact| / max(E_int, E_kin, |W_ext|)
  // KE + IE - E0 - W_ext - W_damping - W_contact [J]: > 0 energy created by the
  // integration (spurious growth), < 0 energy lost without being booked.
  double balance_J() const;
  double balance_error() const;
};

// Wall time spent per stage of the step [s] (filled when State3d::time_stages is set).
struct StageTimes {
  double internal_forces_s = 0.0;  // element kernels + gather
  double contact_s = 0.0;          // road contact
  double rest_s = 0.0;             // pressure, damping, rim, update, energies
};

struct State3d {
  std::vector<double> x, y, z;     // current node positions
  std::vector<double> vx, vy, vz;  // velocities at t - dt/2
  std::vector<double> fx, fy, fz;  // total nodal force at t
  // The parts of it from the inflation pressure and from road or terrain contact:
  // step3d books their work with the velocity at t, the mean of the half steps.
  std::vector<double> pressure_fx, pressure_fy, pressure_fz;
  std::vector<double> contact_fx, contact_fy, contact_fz;
  std::vector<double> rim_node_v_old;  // rim node velocities at t - dt/2 (x, y, z per rim node)
  std::vector<double> element_force;  // batched: Hex8Batches::force_offset
  std::vector<double> element_energy;     // strain + hourglass [J]
  std::vector<double> element_hourglass;  // hourglass part [J]
  std::vector<double> element_viscous_power;  // bulk viscosity [W]
  std::vector<double> rim_offset;   // rim node offsets at angle 0 (x, z) per rim node
  std::vector<int> rim_nodes;
  RimState rim;
  RoadState road;
  TerrainCoupling terrain;
  Energies energy;
  double pressure_Pa = 0.0;
  double damping_per_s = 0.0;       // mass-proportional (dynamic relaxation)
  double time_s = 0.0;
  double dt_s = 0.0;
  std::uint64_t step = 0;
  bool time_stages = false;
  StageTimes stage_times;
};

// The 3D state from reference positions `current` (e.g. the inflated state
// revolved), at rest; the rim node at the origin.
State3d make_state3d(const Model3d& model, const std::vector<Eigen::Vector3d>& current,
                     double rim_mass_kg, double rim_inertia_kg_m2);

// The rigid road at z = height_m with its friction and penalty scale (0: 0.1).
void set_road(State3d& s, double height_m, double friction_coefficient, double penalty_scale);
// The height of the lowest outer (road contact) node.
double lowest_contact_z(const Model3d& model, const State3d& s);
// Puts a flat road `gap` below the lowest outer node.
void place_road(const Model3d& model, State3d& s, double gap_m, double friction_coefficient,
                double penalty_scale);

// The stages of one explicit step of size s.dt_s (see the top of this file).
// The nodal forces at t: element forces, gather, inflation pressure, road contact.
void compute_forces(const Model3d& model, State3d& s);
// The terrain's loads of the window (s.terrain.loads) into the nodal forces, their
// impulse booked; moves the window's sub-step count on.
void add_terrain_loads(State3d& s);
// At a window's start, when the surface is sent: the impulse of the window
// just completed counts (the terrain books the same windows).
void commit_window_impulse(TerrainCoupling& t);
// Damping, rim, central-difference update, energies. Returns false if a value went non-finite.
bool integrate(const Model3d& model, State3d& s, const RimDrive& drive);
// The failure message of a step that integrate() found non-finite: the time,
// the inverted element or the node, and the largest contact load.
std::string non_finite_message(const Model3d& model, const State3d& s);
// compute_forces + integrate: one step of the tyre on its own (rigid road).
bool step3d(const Model3d& model, State3d& s, const RimDrive& drive);

// Joins a terrain solver: offers s.terrain.surface and the stable step s.dt_s
// through the port, and fills the coupling window the coupler answers with equal
// sub-steps no larger than the stable step (s.dt_s, s.terrain.substeps). Returns the window.
// A restart joins at its checkpoint's exchange (s.terrain.exchange) and time.
double connect_to_terrain(TerrainPort& port, State3d& s);
// A step on a terrain (docs/coupling.md) is, at a coupling window's start,
//   send_surface -> compute_forces -> receive_loads -> add_terrain_loads -> integrate
// so that the terrain works on the surface while the element forces are computed;
// on the window's other sub-steps  compute_forces -> add_terrain_loads -> integrate.
// A coupled run (cosim_coupling/coupled_participant.hpp) calls the first three as
// its exchange (exchange_with_terrain) and the rest after it
// (complete_step_on_terrain). The exchange's wall time is added to exchange_s.
//
// The surface near the terrain (below its band or the particles' last reach) out.
void send_surface(State3d& s, TerrainPort& port, double& exchange_s);
// The loads of the same exchange in, and their totals; throws cosim::Error if the terrain is gone.
void receive_loads(State3d& s, TerrainPort& port, double& exchange_s);
// send_surface -> compute_forces -> receive_loads.
void exchange_with_terrain(const Model3d& model, State3d& s, TerrainPort& port, double& exchange_s);
// compute_forces (unless the exchange computed them) -> add_terrain_loads ->
// integrate; throws cosim::Error if the state went non-finite.
void complete_step_on_terrain(const Model3d& model, State3d& s, const RimDrive& drive, bool forces_computed);

// Kinetic damping (Cundall 1976; Underwood 1983): sets every velocity (nodes and
// rim) to zero. Called when the kinetic energy has passed a peak, it drains the
// energy of the dominant mode; used to bring a loaded tyre to rest.
void zero_velocities(State3d& s);

// Tread-centre radial position etc.: distance of node i from the rim node in the x-z plane.
double radial_position(const State3d& s, int node);

}  // namespace tyre_fe
