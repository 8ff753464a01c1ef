#pragma once
// Penalty contact between the SPH particles and a deformable surface owned by
// another solver (the tyre's outer surface, sent every step): node-to-surface
// contact with the particles as the slave points (Belytschko, Liu & Moran 2000,
// ch. 10, penalty method), Coulomb friction per facet.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "cosim/surface_exchange.hpp"

namespace snow_sph {

// The surface another solver owns (world frame, SI): nodes and quad facets.
// Facet nodes are ordered so that the right-hand normal (x2 - x0) x (x3 - x1)
// points OUT of the body that owns the surface (towards the terrain).
struct ContactSurface {
  std::vector<double> x, y, z;              // node positions [m]
  std::vector<double> vx, vy, vz;           // node velocities [m/s]
  std::vector<std::uint32_t> facet_nodes;   // 4 node indices per facet
  std::vector<double> friction_coefficient; // one per facet (Coulomb mu >= 0)
  // Each facet's number in the owner's surface (stable from step to step, while
  // the facets sent change), for the friction history; empty: the index here.
  std::vector<std::uint32_t> facet_id;
  // Lumped mass of each node [kg] as the owner integrates it (empty: not known).
  std::vector<double> node_mass_kg;
  // Per facet, 1 for a face of a sipe (FacetTag::sipe_wall; empty: none). The
  // tyre's sipes are zero-width slits, their two faces coincident: what lies in
  // front of one face is the rubber behind the other, so a particle can touch a
  // face only from inside the tread, never from the water or snow. The thesis's
  // sipes are 1 mm wide, narrower than any particle here (5-20 mm), so none
  // enters one either. The faces are left out of the contact; a particle at a
  // sipe's mouth meets the tread top on both sides of it.
  std::vector<char> closed_slit;
  std::size_t facet_count() const { return facet_nodes.size() / 4; }
};

// The contact surface of one exchange from the owner's topology and the state it
// sent (cosim/surface_exchange.hpp): the nodes sent, the facets sent with their
// corners renumbered to those nodes, their friction, ids and node masses.
// Throws cosim::Error if a facet has a node that was not sent. `scratch` is
// reused from call to call.
void assemble_contact_surface(const cosim::SurfaceTopology& topology, const cosim::SurfaceState& state,
                              ContactSurface& out, std::vector<std::int64_t>& scratch);

// The largest coupling window over which the surface's owner may hold this
// contact's loads on its nodes (multi-rate coupling; docs/coupling.md,
// "Stability of the held loads"). A node a carrying mass m_a over the area A_a
// (a quarter of each facet it belongs to) meets the particles' penalty k per
// particle, one particle per dx^2 of surface: Gershgorin's bound on the coupled
// node-particle system gives omega^2 <= 2 k A_a / (m_a dx^2), and central
// difference with the loads held over the window is stable for omega dt < 2:
//   dt_w <= sqrt(2 m_a dx^2 / (k A_a)).
// Returns the smallest over the nodes (infinity without node masses).
double held_load_window_limit(const ContactSurface& surface, double stiffness_N_per_m, double spacing_m);

// The elastic stick of every particle-facet contact, carried from one call to
// the next: the tangential spring force and the facet (with its normal then),
// grouped by the particles' stable ids. Owned by the caller; start it empty.
struct FrictionHistory {
  struct Stick {
    std::uint32_t facet = 0;   // facet id in the owner's numbering
    float normal[3] = {0, 0, 0};  // the contact normal of the last call
    double force[3] = {0, 0, 0};  // elastic tangential force on the particle [N]
  };
  std::vector<std::uint32_t> begin;  // sticks of particle id k: [begin[k], begin[k + 1])
  std::vector<Stick> sticks;
};

// What the contact did in one step.
struct SurfaceContactResult {
  // Per surface node: force ON THE SURFACE (the reaction of the particles) [N].
  std::vector<double> node_fx, node_fy, node_fz;
  // Per facet: normal force on the surface, compressive > 0 (the particles push
  // along -n) [N]; tangential (friction) force on the surface [N]; the touched
  // part of the facet's area: (2 r)^2 per particle in contact (a particle's share
  // of the terrain surface on a lattice of spacing 2 r; split equally over the
  // facets it touches), at most the facet's area, 0 without contact [m^2];
  // pressure = normal force / touched area [Pa].
  std::vector<double> facet_normal_force_N, facet_tangential_x_N, facet_tangential_y_N, facet_tangential_z_N;
  // Per facet: the pressure (non-friction) force on the surface, -fn along each
  // contact's own direction (the facet normal, or at an edge or corner the line
  // from the closest point to the particle) [N]; pressure + tangential summed
  // over the facets is the total force on the surface.
  std::vector<double> facet_pressure_x_N, facet_pressure_y_N, facet_pressure_z_N;
  std::vector<double> facet_contact_area_m2, facet_pressure_Pa;
  std::vector<std::uint32_t> particles_in_contact;  // per facet
  double total_fx_N = 0, total_fy_N = 0, total_fz_N = 0;  // force on the surface
  double friction_dissipation_J = 0;  // this step: sum ft vt dt
  double damping_dissipation_J = 0;   // this step: contact damping
  double elastic_energy_J = 0;        // in the penalty springs now: sum k delta^2 / 2
  // The deepest contact: the largest penetration radius - d over the contacts
  // (d the particle centre's signed distance to the facet, or to the edge or
  // corner point), before the force's cap at one radius; 0 without contact.
  // Above the radius a particle's centre has crossed the surface.
  double max_penetration_m = 0;
  // Where it is: the particle's centre and the facet (the owner's number; -1 without contact).
  double deepest_x_m = 0, deepest_y_m = 0, deepest_z_m = 0;
  std::int64_t deepest_facet = -1;
  // Particles whose centre is behind a facet they touch (penetration above the
  // radius): water or snow inside the body, which should not happen.
  std::uint32_t particles_behind_surface = 0;
  // Particles drained this call (indices, ascending): pinched against a wall
  // below the film they can resolve (SurfaceContactParameters::drain_film_m).
  // They got no contact force; the caller removes them.
  std::vector<std::uint32_t> drained;
  // The highest point the particles can touch before the next exchange
  // (particle_reach_z); the solver sets it after the call, the owner's next
  // surface reaches down to it.
  double particle_reach_z_m = -std::numeric_limits<double>::max();
};

// The highest point any of the n particles can touch at the next exchange, a
// window later: each one's height advanced over the window as the explicit
// update moves it, with the velocity and the acceleration it has now (the
// contact's force included), z + max(0, (vz + az window) window), plus two
// radii: one the contact's reach, the other for what the particle's
// neighbours change in its acceleration within the window. A surface that
// reaches down to it misses no particle; lowest double without particles.
double particle_reach_z(std::size_t n, const double* z, const double* vz, const double* az, double window_s,
                        double particle_radius_m);

// The closest point to p on the triangle abc, and its barycentric weights w
// (Ericson, Real-Time Collision Detection, 2005, 5.1.5: Voronoi regions of the
// vertices, edges and face).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c, double w[3]);

// The sparse loads that go back to the surface's owner: the nodes and facets of
// `state` that carry any, in the owner's numbering, with the state's exchange and time.
void sparse_surface_loads(const cosim::SurfaceState& state, const SurfaceContactResult& result,
                          cosim::SurfaceLoads& out);

struct SurfaceContactParameters {
  double particle_radius_m = 0;  // half the particle spacing: contact below this distance
  double stiffness_N_per_m = 0;  // penalty stiffness per particle
  double damping_ratio = 0.2;    // of critical, sqrt(k m): normal (only while approaching) and tangential
  double tangential_stiffness_ratio = 1.0;  // k_t / k of the elastic stick
  double max_depth_m = 0;        // particles deeper than this behind a facet are ignored (0: 2 radius)
  // A film thinner than a particle cannot be resolved by particles: a drainable
  // particle that a facet facing one of `walls` (within 45 degrees) presses
  // into a gap thinner than `drain_film_m` between the facet and the wall,
  // measured along the wall's normal through the particle, has been squeezed
  // out of the resolved flow. It gets no contact force and is listed in
  // SurfaceContactResult::drained (0: nothing drains).
  struct Wall {
    int axis = 2;            // 0, 1, 2: x, y, z
    double position_m = 0;   // the plane's coordinate along the axis
    int inside_sign = 1;     // +1: the terrain lies at larger coordinates
  };
  std::vector<Wall> walls;
  double drain_film_m = 0;
};

// For every particle i < n_particles, its contacts with the facets near it:
//  - face contacts: every facet whose plane the particle penetrates, gap
//    d = (x_i - centroid) . n below the radius and above -max_depth, with its
//    projection inside the facet (the quad as triangles 0-1-2 and 0-2-3). All
//    are summed, so that in a concave corner (a groove's floor and wall) the
//    force is the gradient of one potential;
//  - otherwise an edge or corner contact with the closest point c of the
//    nearest facet (Ericson, Real-Time Collision Detection 2005, 5.1.5), along
//    the line from c to the particle (a convex ridge pushes away from itself).
// Each contact: penetration delta = radius - d (capped at one radius; the
// result's max_penetration_m is the largest before the cap) gives
// fn = max(0, k delta - c_d v_n) along the normal (v_n: normal velocity of the
// particle relative to the surface at the contact point; damping only while
// approaching), and Coulomb friction with an elastic stick: a tangential spring
// k_t = ratio k, loaded by the relative tangential motion, damped by
// c_t = 2 damping_ratio sqrt(k_t m) while it sticks, and capped at mu fn, where
// it slides (the spring is then the cap). A sticking particle holds a steady
// tangential load with an elastic offset of at most mu fn / k_t and no creep.
// The spring is carried between calls in `history` (by the stable `particle_id`
// and the facet id; a contact that moved onto a neighbouring facet within 30
// degrees keeps its spring, turned into the new tangent plane). Without a
// history every contact starts unloaded.
// The force on the particle is added to (ax, ay, az)[i] / mass[i]; the opposite
// force goes to the facet's nodes with the bilinear shape functions at the
// contact point (linear along an edge), so momentum is conserved exactly.
// `drainable` (per particle, 1 for water; null: none) marks the particles that
// drain from a film thinner than params.drain_film_m against params.walls: they
// get no contact and are listed in loads.drained.
// `loads` is overwritten. The result does not depend on the number of OpenMP threads.
void surface_contact(const ContactSurface& surface, const SurfaceContactParameters& params,
                     std::size_t n_particles, const double* x, const double* y, const double* z,
                     const double* vx, const double* vy, const double* vz, const double* mass,
                     double dt, double* ax, double* ay, double* az, SurfaceContactResult& loads,
                     FrictionHistory* history = nullptr, const std::uint32_t* particle_id = nullptr,
                     const std::uint8_t* drainable = nullptr);

// Central-difference limit of a penalty spring on the lightest particle: 2 sqrt(m / k).
double surface_contact_stable_dt(double min_particle_mass_kg, double stiffness_N_per_m);

}  // namespace snow_sph
