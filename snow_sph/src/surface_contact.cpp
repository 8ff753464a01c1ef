// Penalty contact of the particles with a coupled surface (docs/sph.md,
// "Contact with a coupled surface"), as stages: facet geometry and binning
// (facet_grid.hpp) -> per particle, the facets it touches (contact) and their
// elastic-stick friction -> serial scatter of the reactions onto the facet
// nodes and facets -> the sticks carried to the next call -> contact areas.
#include "snow_sph/surface_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cosim/error.hpp"
#include "cosim/parallel.hpp"
#include "cosim/penalty_contact.hpp"
#include "cosim/quad_facet.hpp"
#include "snow_sph/facet_grid.hpp"
#include "snow_sph/facet_projection.hpp"
#include "snow_sph/surface_contact_slots.hpp"

namespace snow_sph {
namespace {

using V3 = Eigen::Vector3d;

constexpr double kSameSurfaceCos = 0.99619469809;  // cos 5 deg
constexpr double kStickInheritCos = 0.86602540378;  // cos 30 deg: a stick moves onto a neighbouring facet


// --- checks and the loads' arrays ---

void check_surface(const ContactSurface& s) {
  const std::size_t nn = s.x.size(), nf = s.facet_count();
  if (s.facet_nodes.size() != 4 * nf || s.friction_coefficient.size() != nf || s.y.size() != nn ||
      s.z.size() != nn || s.vx.size() != nn || s.vy.size() != nn || s.vz.size() != nn ||
      (!s.facet_id.empty() && s.facet_id.size() != nf))
    throw cosim::Error("contact surface: node or facet arrays differ in length");
  for (std::uint32_t n : s.facet_nodes)
    if (n >= nn) throw cosim::Error("contact surface: facet node " + std::to_string(n) + " out of range");
}

void reset_loads(SurfaceContactResult& loads, std::size_t nn, std::size_t nf) {
  loads = SurfaceContactResult{};
  loads.node_fx.assign(nn, 0.0), loads.node_fy.assign(nn, 0.0), loads.node_fz.assign(nn, 0.0);
  for (auto* v : {&loads.facet_normal_force_N, &loads.facet_pressure_x_N, &loads.facet_pressure_y_N,
                  &loads.facet_pressure_z_N, &loads.facet_tangential_x_N, &loads.facet_tangential_y_N,
                  &loads.facet_tangential_z_N, &loads.facet_contact_area_m2, &loads.facet_pressure_Pa})
    v->assign(nf, 0.0);
  loads.particles_in_contact.assign(nf, 0);
}

// --- facet geometry and binning ---

// Unit outward normals and areas ((x2 - x0) x (x3 - x1) / 2, exact for a planar quad).
struct FacetGeometry {
  std::vector<V3> normal;
  std::vector<double> area;
};

FacetGeometry facet_geometry(const ContactSurface& s) {
  const std::size_t nf = s.facet_count();
  FacetGeometry g;
  g.normal.resize(nf);
  g.area.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const V3 a = facet_area_vector(s, f);
    g.area[f] = a.norm();
    g.normal[f] = cosim::unit_normal(a);
  }
  return g;
}

// What every particle's contact reads.
struct ContactContext {
  const ContactSurface& s;
  const SurfaceContactParameters& params;
  const FacetGeometry& geometry;
  const FacetGrid& grid;
  double radius, k, depth, dt;
  V3 node(std::uint32_t n) const { return V3(s.x[n], s.y[n], s.z[n]); }
};

// --- friction ---

// A particle's sticks of the last call (each can be taken over once).
struct OldSticks {
  const FrictionHistory::Stick* stick = nullptr;
  int count = 0;
  bool taken[kMaxContacts] = {false, false, false, false, false, false};
};

struct Friction {
  V3 ft = V3::Zero();      // on the particle
  V3 spring = V3::Zero();  // the elastic stick after this call
  double dissipated_J = 0.0;
};

// Coulomb friction with an elastic stick (penalty friction with elastic
// slip: Wriggers, Computational Contact Mechanics, 2006, 5.2.2; Abaqus
// Analysis User's Guide 37.1.5). The spring of the last call (same facet,
// or a neighbouring one within 30 degrees: the particle rolled over an
// edge of the tread) is turned into this tangent plane, loaded by this
// step's relative tangential motion and capped at mu fn. The spring has
// the normal penalty's stiffness (ratio 1), so it adds to the particle
// and to the facet's nodes no more than the normal spring the scenes
// already size for stability; its damper is the normal one's fraction of
// critical. Sticking therefore needs no slip speed (the damper
// m / (20 dt) used before needed 0.2-0.5 m/s of creep for full friction).
Friction stick_friction(const ContactContext& c, OldSticks& old, std::uint32_t fid, std::int32_t f, const V3& n,
                        const V3& vt_vec, double fn, double m) {
  const double k = c.k, dt = c.dt;
  V3 spring = V3::Zero();
  int from = -1;
  double best_cos = kStickInheritCos;
  for (int o = 0; o < old.count; ++o) {
    if (old.taken[o]) continue;
    if (old.stick[o].facet == fid) {
      from = o;
      break;
    }
    const double cs = n.dot(V3(old.stick[o].normal[0], old.stick[o].normal[1], old.stick[o].normal[2]));
    if (cs >= best_cos) best_cos = cs, from = o;
  }
  if (from >= 0) {
    old.taken[from] = true;
    const V3 prev(old.stick[from].force[0], old.stick[from].force[1], old.stick[from].force[2]);
    const V3 in_plane = prev - prev.dot(n) * n;
    const double norm = in_plane.norm();
    if (norm > 0.0) spring = in_plane * (prev.norm() / norm);
  }
  const double mu = c.s.friction_coefficient[f];
  const double kt = c.params.tangential_stiffness_ratio * k;
  const double cap = mu * fn;
  spring -= kt * dt * vt_vec;
  V3 ft = V3::Zero();
  double friction_J = 0.0;
  const double spring_norm = spring.norm();
  const cosim::penalty::CoulombCap cone = cosim::penalty::coulomb_cap(spring_norm, cap);
  if (cap <= 0.0 || kt <= 0.0) {
    spring = V3::Zero();
  } else if (cone.sliding) {
    // Sliding: the spring stays at the cap; the excess is slip, mu fn times its length dissipated.
    friction_J = cosim::penalty::slip_dissipation(spring_norm, cap, kt);
    spring *= cone.scale;
    ft = spring;
  } else {
    // Sticking: spring plus damper, the sum held within the cone.
    const double c_t = cosim::penalty::damping_coefficient(c.params.damping_ratio, kt, m);
    ft = spring - c_t * vt_vec;
    const cosim::penalty::CoulombCap damped = cosim::penalty::coulomb_cap(ft.norm(), cap);
    if (damped.sliding) ft *= damped.scale;
    friction_J = std::max(0.0, -(ft - spring).dot(vt_vec)) * dt;
  }
  Friction out;
  out.ft = ft, out.spring = spring, out.dissipated_J = friction_J;
  return out;
}

// --- contact ---

// Penalty force of one facet along `n` with penetration `delta`, friction
// against the facet's velocity at the contact point (weights w).
void add_contact(const ContactContext& c, ParticleContacts& pc, OldSticks& old, const V3& vp, double m,
                 std::int32_t f, const V3& n, double delta, const double w[4]) {
  if (pc.count == kMaxContacts) return;
  const ContactSurface& s = c.s;
  const double k = c.k, dt = c.dt;
  const std::uint32_t* q = &s.facet_nodes[4 * f];
  V3 vs = V3::Zero();
  for (int a = 0; a < 4; ++a) vs += w[a] * V3(s.vx[q[a]], s.vy[q[a]], s.vz[q[a]]);
  const V3 rel = vp - vs;
  const double vn = rel.dot(n);
  // A particle pushed past the facet plane (penetration beyond its radius)
  // is pushed back with the force of a radius's penetration: no larger
  // impulse reaches the light tread nodes of a sipe-cut block.
  const double penetration = delta;
  delta = std::min(delta, c.radius);
  const double c_d = cosim::penalty::damping_coefficient(c.params.damping_ratio, k, m);
  const cosim::penalty::NormalForce normal =
      cosim::penalty::normal_force(k, delta, vn, c_d, cosim::penalty::Damping::approach_only);
  const double fn = normal.force_N;
  const V3 vt_vec = rel - vn * n;
  const std::uint32_t fid = s.facet_id.empty() ? static_cast<std::uint32_t>(f) : s.facet_id[f];
  const Friction friction = stick_friction(c, old, fid, f, n, vt_vec, fn, m);
  const V3& ft = friction.ft;
  const V3& spring = friction.spring;
  const double kt = c.params.tangential_stiffness_ratio * k;
  const double ft_mag = ft.norm();
  const V3 force = fn * n + ft;
  Contact& ct = pc.c[pc.count++];
  ct.facet = f;
  ct.facet_id = fid;
  for (int a = 0; a < 4; ++a) ct.w[a] = w[a];
  for (int a = 0; a < 3; ++a) ct.f[a] = force[a], ct.ft[a] = ft[a], ct.normal[a] = n[a], ct.spring[a] = spring[a];
  ct.fn = fn;
  ct.penetration_m = penetration;
  ct.friction_J = friction.dissipated_J;
  ct.damping_J = cosim::penalty::approach_damping_power(normal, vn) * dt;
  ct.elastic_J = 0.5 * k * delta * delta + (ft_mag > 0.0 ? 0.5 * spring.squaredNorm() / kt : 0.0);
}

// The facets a particle touches: every facet whose plane the particle
// penetrates with its projection inside the facet (faces), else the closest
// point of the cell's facets (for the edge and corner fall-back).
struct Face {
  std::int32_t facet;
  double delta, w[4];
};
struct FacetSearch {
  Face faces[kMaxContacts];
  int face_count = 0;
  double best = std::numeric_limits<double>::infinity();
  std::int32_t best_facet = -1;
  double best_w[4] = {0, 0, 0, 0};
  V3 best_point = V3::Zero();
};

FacetSearch search_facets(const ContactContext& c, const V3& p, int cell) {
  const ContactSurface& s = c.s;
  const FacetGrid& grid = c.grid;
  const double radius = c.radius, depth = c.depth;
  FacetSearch r;
  for (std::uint32_t e = grid.begin[cell]; e < grid.begin[cell + 1]; ++e) {
    const std::uint32_t f = grid.entries[e];
    if (c.geometry.area[f] <= 0) continue;
    const std::uint32_t* q = &s.facet_nodes[4 * f];
    const V3 a = c.node(q[0]), b = c.node(q[1]), cc = c.node(q[2]), d = c.node(q[3]);
    const V3& n = c.geometry.normal[f];
    const double gap = (p - cosim::quad_centroid(a, b, cc, d)).dot(n);
    if (gap < radius && gap > -depth) {
      const V3 proj = p - gap * n;
      double w3[3];
      double w[4] = {0, 0, 0, 0};
      bool inside = inside_triangle(proj, a, b, cc, w3);
      if (inside) {
        w[0] = w3[0], w[1] = w3[1], w[2] = w3[2];
      } else if (inside_triangle(proj, a, cc, d, w3)) {
        inside = true, w[0] = w3[0], w[2] = w3[1], w[3] = w3[2];
      }
      if (inside) {
        const V3 corners[4] = {a, b, cc, d};
        bilinear_weights(proj, corners, w);
        if (r.face_count < kMaxContacts) {
          Face& fc = r.faces[r.face_count++];
          fc.facet = static_cast<std::int32_t>(f), fc.delta = radius - gap;
          for (int a = 0; a < 4; ++a) fc.w[a] = w[a];
        }
        continue;
      }
    }
    // Otherwise the closest point, for the edge and corner fall-back below.
    double w1[3], w2[3];
    const V3 p1 = closest_on_triangle(p, a, b, cc, w1);
    const V3 p2 = closest_on_triangle(p, a, cc, d, w2);
    const double d1 = (p - p1).squaredNorm(), d2 = (p - p2).squaredNorm();
    if (std::min(d1, d2) < r.best) {
      r.best = std::min(d1, d2), r.best_facet = static_cast<std::int32_t>(f);
      if (d1 <= d2) r.best_w[0] = w1[0], r.best_w[1] = w1[1], r.best_w[2] = w1[2], r.best_w[3] = 0, r.best_point = p1;
      else r.best_w[0] = w2[0], r.best_w[1] = 0, r.best_w[2] = w2[1], r.best_w[3] = w2[2], r.best_point = p2;
    }
  }
  return r;
}

// The film between a facet (contact direction n, the particle at `gap` from
// it along n) and each wall it faces, along the wall's normal through the
// particle: the particle's distance to the wall plus the gap's projection.
bool pinched(const SurfaceContactParameters& params, const V3& p, const V3& n, double gap) {
  constexpr double kFacingCos = 0.70710678118;  // cos 45 deg
  for (const SurfaceContactParameters::Wall& w : params.walls) {
    const double facing = -w.inside_sign * n[w.axis];
    if (facing < kFacingCos) continue;
    const double to_wall = w.inside_sign * (p[w.axis] - w.position_m);
    if (to_wall + gap / facing < params.drain_film_m) return true;
  }
  return false;
}

// A water particle squeezed against a wall below the film it resolves leaves
// the flow (SurfaceContactParameters::drain_film_m) instead of being crushed.
bool squeezed_out(const ContactContext& c, const FacetSearch& r, const V3& p, bool edge) {
  const double radius = c.radius;
  const std::vector<V3>& normal = c.geometry.normal;
  bool squeezed = false;
  for (int a = 0; a < r.face_count && !squeezed; ++a)
    squeezed = pinched(c.params, p, normal[r.faces[a].facet], radius - r.faces[a].delta);
  if (edge && !squeezed) {
    const V3 offset = p - r.best_point;
    const double distance = std::sqrt(r.best);
    if (offset.dot(normal[r.best_facet]) > 0 && distance > 1e-12)
      squeezed = pinched(c.params, p, V3(offset / distance), distance);
  }
  return squeezed;
}

// The contacts of one particle at p in grid cell `cell`.
void particle_contacts(const ContactContext& c, const V3& p, const V3& vp, double m, int cell, bool can_drain,
                       OldSticks& old, ParticleContacts& pc) {
  const double radius = c.radius;
  const std::vector<V3>& normal = c.geometry.normal;
  // Face contacts: summing them (not only the closest) keeps the force a
  // gradient of one potential in concave corners (a groove's floor and
  // walls), where switching between closest facets pumped energy.
  const FacetSearch r = search_facets(c, p, cell);
  const bool edge = r.face_count == 0 && r.best_facet >= 0 && r.best < radius * radius;
  if (can_drain && squeezed_out(c, r, p, edge)) {
    pc.drained = true;
    return;
  }
  // Neighbouring facets within 5 degrees of each other are one surface: a
  // particle on their shared edge (inside both, the edge included) or behind
  // both near a gentle convex edge is pushed once, by the deeper (then the
  // lower-numbered) facet. Facets at larger angles (a groove's floor and
  // wall) both push.
  const Face* faces = r.faces;
  for (int a = 0; a < r.face_count; ++a) {
    bool keep = true;
    for (int b = 0; b < r.face_count && keep; ++b) {
      if (a == b || normal[faces[a].facet].dot(normal[faces[b].facet]) < kSameSurfaceCos) continue;
      keep = faces[a].delta > faces[b].delta || (faces[a].delta == faces[b].delta && faces[a].facet < faces[b].facet);
    }
    if (keep) add_contact(c, pc, old, vp, m, faces[a].facet, normal[faces[a].facet], faces[a].delta, faces[a].w);
  }
  // Edge and corner contact (a convex ridge, e.g. a block's edge): no face
  // holds the particle's projection; the closest point pushes it away from
  // itself, along the line from that point to the particle.
  if (edge) {
    const V3 offset = p - r.best_point;
    const double distance = std::sqrt(r.best);
    if (offset.dot(normal[r.best_facet]) > 0 && distance > 1e-12)
      add_contact(c, pc, old, vp, m, r.best_facet, V3(offset / distance), radius - distance, r.best_w);
  }
}

}  // namespace

void surface_contact(const ContactSurface& s, const SurfaceContactParameters& params, std::size_t n_particles,
                     const double* x, const double* y, const double* z, const double* vx, const double* vy,
                     const double* vz, const double* mass, double dt, double* ax, double* ay, double* az,
                     SurfaceContactResult& loads, FrictionHistory* history, const std::uint32_t* particle_id,
                     const std::uint8_t* drainable) {
  check_surface(s);
  const std::size_t nn = s.x.size(), nf = s.facet_count();
  reset_loads(loads, nn, nf);
  auto id_of = [&](std::size_t i) { return particle_id ? particle_id[i] : static_cast<std::uint32_t>(i); };
  if (nf == 0 || n_particles == 0) {
    if (history) *history = FrictionHistory{};
    return;
  }
  // Geometry and binning.
  const double radius = params.particle_radius_m, k = params.stiffness_N_per_m;
  const double depth = params.max_depth_m > 0 ? params.max_depth_m : 2.0 * radius;
  const double reach = std::max(radius, depth);
  const FacetGeometry geometry = facet_geometry(s);
  const FacetGrid grid = bin_facets(s, reach);
  const ContactContext context{s, params, geometry, grid, radius, k, depth, dt};
  // Per-particle contact slots, kept between calls (a fresh 100k-particle
  // buffer cost 60 ms per call to allocate and clear).
  // (A reference, so that the OpenMP threads share the calling thread's buffer.)
  static thread_local std::vector<ParticleContacts> buffer;
  if (buffer.size() < n_particles) buffer.resize(n_particles);
  std::vector<ParticleContacts>& contacts = buffer;
  const bool can_drain = drainable && params.drain_film_m > 0 && !params.walls.empty();
  // Contact and friction, per particle, into its acceleration.
  cosim::parallel_for("sph.surface_contact", n_particles, [&](std::size_t i) {
    contacts[i].count = 0;
    contacts[i].drained = false;
    const V3 p(x[i], y[i], z[i]);
    int cell_ijk[3];
    if (!grid.cell_of(p, cell_ijk)) return;
    const int cell = grid.index(cell_ijk[0], cell_ijk[1], cell_ijk[2]);
    const double m = mass[i];
    const V3 vp(vx[i], vy[i], vz[i]);
    ParticleContacts& pc = contacts[i];
    OldSticks old;
    if (history) {
      const std::uint32_t id = id_of(i);
      if (static_cast<std::size_t>(id) + 1 < history->begin.size()) {
        old.stick = history->sticks.data() + history->begin[id];
        old.count = std::min<int>(kMaxContacts, static_cast<int>(history->begin[id + 1] - history->begin[id]));
      }
    }
    particle_contacts(context, p, vp, m, cell, can_drain && drainable[i], old, pc);
    if (pc.drained) return;
    for (int k2 = 0; k2 < pc.count; ++k2) {
      const Contact& ct = pc.c[k2];
      ax[i] += ct.f[0] / m, ay[i] += ct.f[1] / m, az[i] += ct.f[2] / m;
    }
  });
  // Scatter onto the facet nodes and facets, the sticks for the next call, contact areas.
  scatter_loads(s, params, n_particles, x, y, z, contacts, loads);
  if (history) *history = next_history(n_particles, contacts, particle_id);
  facet_contact_areas(radius, n_particles, contacts, geometry.area, loads);
}

}  // namespace snow_sph
