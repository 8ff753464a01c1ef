#pragma once
// The fields of every topic of idl/cosim_topics.idl, written once as C++: the
// IDL's mirror, from which the vendor-neutral topic structs
// (cosim_transport/topics.hpp), both vendors' conversions (transport/fast,
// transport/cyclone), the solvers' exchange types (cosim/surface_exchange.hpp)
// and their copies to and from the topics (coupling/src/exchange_topics.cpp)
// are expanded. tests/common/test_wire_fields.cpp reads the IDL and checks this table
// against it field by field (names, types, order), so the two cannot drift.
//
// Each COSIM_WIRE_FIELDS_<Struct>(F) calls F(type, name, initial value) once
// per field, in the IDL's order. Every topic starts with `SampleHeader header`
// (the IDL's rule): the table lists the fields after it. Adding a field: add it
// to the IDL and here (see idl/README.md), then fill it and read it.
//
// Types are spelled as the neutral structs hold them (FacetTag is cosim's;
// ControlKind and Role are cosim::transport's, named where the table is
// expanded). Units are in the names; the IDL's comments say what each field is.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

// First field of every sample.
#define COSIM_WIRE_FIELDS_SampleHeader(F)                                                       \
  F(std::uint64_t, run_id, 0) /* random per run (new_run_id()), shared by all its processes */ \
  F(std::uint64_t, step, 0)                                                                     \
  F(double, sim_time_s, 0.0)

// The tyre's contact surface, published once: the tyre model's node of each
// surface node, then the surface the two solvers share (SurfaceTopology).
#define COSIM_WIRE_FIELDS_SurfaceMesh(F) \
  F(std::vector<std::uint32_t>, node_ids, {}) /* tyre model node of surface node k */ \
  COSIM_WIRE_FIELDS_SurfaceTopology(F)

// Quad facets of four surface nodes whose right-hand normal
// (x2 - x0) x (x3 - x1) points out of the owner's body.
#define COSIM_WIRE_FIELDS_SurfaceTopology(F)                                                   \
  F(std::vector<double>, x_m, {}) /* reference position per surface node */                   \
  F(std::vector<double>, y_m, {})                                                              \
  F(std::vector<double>, z_m, {})                                                              \
  F(std::vector<std::uint32_t>, facet_nodes, {}) /* 4 surface-node indices per quad facet */   \
  F(std::vector<FacetTag>, facet_tags, {})       /* one per facet */                           \
  F(std::vector<double>, node_mass_kg, {})       /* lumped mass per surface node (empty: not known) */

// Per exchange: the surface nodes near the terrain and the friction per nearby facet.
#define COSIM_WIRE_FIELDS_SurfaceKinematics(F)                                                          \
  F(std::vector<std::uint32_t>, nodes, {}) /* surface-node indices included */                          \
  F(std::vector<double>, x_m, {})          /* current positions, one per entry of nodes */              \
  F(std::vector<double>, y_m, {})                                                                       \
  F(std::vector<double>, z_m, {})                                                                       \
  F(std::vector<double>, vx_mps, {})                                                                    \
  F(std::vector<double>, vy_mps, {})                                                                    \
  F(std::vector<double>, vz_mps, {})                                                                    \
  F(std::vector<std::uint32_t>, facets, {}) /* facets included (all their nodes are) */                 \
  F(std::vector<double>, friction_coefficient, {}) /* one per facet, set by the coupler; empty from the owner */

// Per exchange, sparse: the loads on the contacted nodes and facets.
// particle_reach_z_m is the highest point the terrain's particles can touch
// before the next exchange (the owner sends every facet with a node below it);
// the lowest double: nothing to touch.
#define COSIM_WIRE_FIELDS_ContactLoads(F)                                                                  \
  F(std::vector<std::uint32_t>, nodes, {}) /* contacted surface nodes */                                  \
  F(std::vector<double>, fx_N, {})         /* force on the surface node, global frame */                  \
  F(std::vector<double>, fy_N, {})                                                                         \
  F(std::vector<double>, fz_N, {})                                                                         \
  F(std::vector<std::uint32_t>, facets, {}) /* contacted facets */                                        \
  F(std::vector<double>, normal_force_N, {}) /* along the facet normal, compressive > 0 */                \
  F(std::vector<double>, pressure_x_N, {})   /* pressure part, along each contact's own direction */      \
  F(std::vector<double>, pressure_y_N, {})                                                                 \
  F(std::vector<double>, pressure_z_N, {})                                                                 \
  F(std::vector<double>, tangential_x_N, {})                                                               \
  F(std::vector<double>, tangential_y_N, {})                                                               \
  F(std::vector<double>, tangential_z_N, {})                                                               \
  F(std::vector<double>, contact_area_m2, {})                                                              \
  F(std::vector<double>, pressure_Pa, {})                                                                  \
  F(double, particle_reach_z_m, -std::numeric_limits<double>::max())

// Per step, from the tyre: the rigid rim.
#define COSIM_WIRE_FIELDS_WheelState(F)                                                     \
  F(double, rim_x_m, 0.0)                                                                   \
  F(double, rim_z_m, 0.0)                                                                   \
  F(double, rotation_angle_rad, 0.0) /* about y */                                          \
  F(double, forward_speed_mps, 0.0)                                                         \
  F(double, spin_rate_radps, 0.0)                                                           \
  F(double, applied_torque_Nm, 0.0)                                                         \
  F(double, reaction_moment_y_Nm, 0.0) /* RM2 */                                            \
  F(double, wheel_load_N, 0.0)                                                              \
  F(double, rim_longitudinal_force_N, 0.0) /* the tyre's force on the rim along x, forward + */

// Per step, from the coupler: the thesis's force decomposition (coupler/forces.hpp).
#define COSIM_WIRE_FIELDS_ForceSummary(F)                   \
  F(double, traction_force_N, 0.0)           /* F3 */       \
  F(double, motion_resistance_N, 0.0)        /* F1 */       \
  F(double, groove_force_N, 0.0)             /* F2 */       \
  F(double, rolling_resistance_force_N, 0.0) /* F5 */       \
  F(double, drawbar_pull_N, 0.0)                            \
  F(double, net_longitudinal_pressure_force_N, 0.0)         \
  F(double, sinkage_m, 0.0)                                 \
  F(double, contact_area_m2, 0.0)                           \
  F(double, rolling_resistance_moment_Nm, 0.0) /* RRM: F5 = RRM / r */

// Start handshake, run start and stop, liveness and failures.
#define COSIM_WIRE_FIELDS_RunControl(F)                                                     \
  F(ControlKind, kind, ControlKind::hello)                                                  \
  F(Role, sender, Role::any)                                                                \
  F(Role, addressee, Role::any) /* Role::any for broadcasts */                              \
  F(double, proposed_time_step_s, 0.0) /* sender's stable step (0 if none) */               \
  F(double, agreed_time_step_s, 0.0)   /* set with ControlKind::start (0 otherwise) */      \
  F(std::string, reason, {})           /* free text (failure cause, stop reason) */

// Every topic, in the IDL's order: T(Struct) once each (what each backend
// converts and the tests compare).
#define COSIM_WIRE_TOPICS(T) \
  T(SurfaceMesh)             \
  T(SurfaceKinematics)       \
  T(ContactLoads)            \
  T(WheelState)              \
  T(ForceSummary)            \
  T(RunControl)
// Every struct of the IDL: the header, then the topics (the IDL test walks it).
#define COSIM_WIRE_STRUCTS(T) T(SampleHeader) COSIM_WIRE_TOPICS(T)

// The expansion most users want: `type name = initial value;`.
#define COSIM_WIRE_DECLARE_FIELD(type, name, init) type name = init;
