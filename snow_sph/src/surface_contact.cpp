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

namespace snow_sph {
namespace {

using V3 = Eigen::Vector3d;

constexpr double kSameSurfaceCos = 0.99619469809;  // cos 5 deg
constexpr double kStickInheritCos = 0.86602540378;  // cos 30 deg: a stick moves onto a neighbouring facet

// Facets binned in a uniform grid over their bounding boxes grown by the reach.
struct FacetGrid {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, cell = 1.0;
  int dims[3] = {1, 1, 1};
  std::vector<std::uint32_t> begin, entries;  // CSR: cell -> facets

  int index(int i, int j, int k) const { return (k * dims[1] + j) * dims[0] + i; }
  bool cell_of(const V3& p, int c[3]) const {
    for (int a = 0; a < 3; ++a) {
      if (p[a] < lo[a] || p[a] > hi[a]) return false;
      c[a] = std::min(dims[a] - 1, static_cast<int>((p[a] - lo[a]) / cell));
    }
    return true;
  }
};

FacetGrid bin_facets(const ContactSurface& s, double reach) {
  FacetGrid g;
  const std::size_t nf = s.facet_count();
  std::vector<double> box(6 * nf);
  double extent = 0.0;
  for (int a = 0; a < 3; ++a) g.lo[a] = 1e300, g.hi[a] = -1e300;
  for (std::size_t f = 0; f < nf; ++f) {
    double* b = &box[6 * f];
    for (int a = 0; a < 3; ++a) b[a] = 1e300, b[3 + a] = -1e300;
    for (int q = 0; q < 4; ++q) {
      const std::uint32_t n = s.facet_nodes[4 * f + q];
      const double p[3] = {s.x[n], s.y[n], s.z[n]};
      for (int a = 0; a < 3; ++a) b[a] = std::min(b[a], p[a] - reach), b[3 + a] = std::max(b[3 + a], p[a] + reach);
    }
    for (int a = 0; a < 3; ++a) {
      extent = std::max(extent, b[3 + a] - b[a]);
      g.lo[a] = std::min(g.lo[a], b[a]), g.hi[a] = std::max(g.hi[a], b[3 + a]);
    }
  }
  // About one grown facet per cell, at most ~4 million cells.
  g.cell = std::max(extent, 1e-6);
  while (true) {
    long total = 1;
    for (int a = 0; a < 3; ++a) g.dims[a] = std::max(1, static_cast<int>(std::ceil((g.hi[a] - g.lo[a]) / g.cell)));
    total = static_cast<long>(g.dims[0]) * g.dims[1] * g.dims[2];
    if (total <= 4000000) break;
    g.cell *= 1.5;
  }
  const std::size_t cells = static_cast<std::size_t>(g.dims[0]) * g.dims[1] * g.dims[2];
  std::vector<std::uint32_t> count(cells + 1, 0);
  auto each_cell = [&](std::size_t f, auto&& visit) {
    int c0[3], c1[3];
    for (int a = 0; a < 3; ++a) {
      c0[a] = std::clamp(static_cast<int>((box[6 * f + a] - g.lo[a]) / g.cell), 0, g.dims[a] - 1);
      c1[a] = std::clamp(static_cast<int>((box[6 * f + 3 + a] - g.lo[a]) / g.cell), 0, g.dims[a] - 1);
    }
    for (int k = c0[2]; k <= c1[2]; ++k)
      for (int j = c0[1]; j <= c1[1]; ++j)
        for (int i = c0[0]; i <= c1[0]; ++i) visit(g.index(i, j, k));
  };
  // A closed slit's faces take no particle (ContactSurface::closed_slit): not binned, never visited.
  auto takes_particles = [&](std::size_t f) { return s.closed_slit.empty() || !s.closed_slit[f]; };
  for (std::size_t f = 0; f < nf; ++f)
    if (takes_particles(f)) each_cell(f, [&](int c) { ++count[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
  g.begin = count;
  g.entries.resize(count[cells]);
  for (std::size_t f = 0; f < nf; ++f)
    if (takes_particles(f)) each_cell(f, [&](int c) { g.entries[count[c]++] = static_cast<std::uint32_t>(f); });
  return g;
}

// The contacts of one particle (at most kMaxContacts facets), kept per
// particle so that the sums are serial and independent of the thread count.
constexpr int kMaxContacts = 6;
struct Contact {
  std::int32_t facet = -1;
  std::uint32_t facet_id = 0;  // in the owner's numbering (the history's key)
  double normal[3] = {0, 0, 0};
  double spring[3] = {0, 0, 0};  // elastic tangential force on the particle after this call
  double w[4] = {0, 0, 0, 0};
  double f[3] = {0, 0, 0};  // force on the particle
  double fn = 0.0, ft[3] = {0, 0, 0};
  double penetration_m = 0.0;  // radius - signed distance, before the cap at one radius
  double friction_J = 0.0, damping_J = 0.0, elastic_J = 0.0;
};
struct ParticleContacts {
  int count = 0;
  bool drained = false;
  Contact c[kMaxContacts];
};

// Bilinear shape functions of the quad at the point q of its surface (inverse
// isoparametric map by Gauss-Newton from the centre; exact for a parallelogram
// after one iteration): the weights with which a point force at q is shared by
// the four nodes, consistent with the tyre's bilinear facet.
void bilinear_weights(const V3& q, const V3 x[4], double w[4]) {
  static const double xi_a[4] = {-1, 1, 1, -1}, eta_a[4] = {-1, -1, 1, 1};
  double xi = 0.0, eta = 0.0;
  for (int it = 0; it < 4; ++it) {
    V3 r = -q, dxi = V3::Zero(), deta = V3::Zero();
    for (int a = 0; a < 4; ++a) {
      r += 0.25 * (1 + xi_a[a] * xi) * (1 + eta_a[a] * eta) * x[a];
      dxi += 0.25 * xi_a[a] * (1 + eta_a[a] * eta) * x[a];
      deta += 0.25 * eta_a[a] * (1 + xi_a[a] * xi) * x[a];
    }
    const double a11 = dxi.dot(dxi), a12 = dxi.dot(deta), a22 = deta.dot(deta);
    const double b1 = -dxi.dot(r), b2 = -deta.dot(r), det = a11 * a22 - a12 * a12;
    if (!(det > 0)) break;
    xi += (a22 * b1 - a12 * b2) / det, eta += (a11 * b2 - a12 * b1) / det;
  }
  xi = std::clamp(xi, -1.0, 1.0), eta = std::clamp(eta, -1.0, 1.0);
  for (int a = 0; a < 4; ++a) w[a] = 0.25 * (1 + xi_a[a] * xi) * (1 + eta_a[a] * eta);
}

// Barycentric coordinates of q (in the plane of abc) in triangle abc; true if inside.
bool inside_triangle(const V3& q, const V3& a, const V3& b, const V3& c, double w[3]) {
  const V3 v0 = b - a, v1 = c - a, v2 = q - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0)) return false;
  const double v = (d11 * d20 - d01 * d21) / den, t = (d00 * d21 - d01 * d20) / den;
  w[0] = 1.0 - v - t, w[1] = v, w[2] = t;
  return w[0] >= 0 && v >= 0 && t >= 0;
}

// Facet f's area vector (cosim::quad_area_vector): its length is the area, exact
// for a planar quad, and it points along the outward normal.
V3 facet_area_vector(const ContactSurface& s, std::size_t f) {
  const std::uint32_t* q = &s.facet_nodes[4 * f];
  auto node = [&](std::uint32_t n) { return V3(s.x[n], s.y[n], s.z[n]); };
  return cosim::quad_area_vector(node(q[0]), node(q[1]), node(q[2]), node(q[3]));
}

}  // namespace

// Closest point to p on triangle abc and its barycentric weights (Ericson,
// Real-Time Collision Detection, 2005, 5.1.5: Voronoi regions of the vertices,
// edges and face).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c, double w[3]) {
  using V3 = Eigen::Vector3d;
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return w[0] = 1, w[1] = 0, w[2] = 0, a;
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return w[0] = 0, w[1] = 1, w[2] = 0, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return w[0] = 1 - v, w[1] = v, w[2] = 0, V3(a + v * ab);
  }
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return w[0] = 0, w[1] = 0, w[2] = 1, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return w[0] = 1 - t, w[1] = 0, w[2] = t, V3(a + t * ac);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return w[0] = 0, w[1] = 1 - t, w[2] = t, V3(b + t * (c - b));
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, t = vc * denom;
  return w[0] = 1 - v - t, w[1] = v, w[2] = t, V3(a + ab * v + ac * t);
}

void assemble_contact_surface(const cosim::SurfaceTopology& topology, const cosim::SurfaceState& state,
                              ContactSurface& s, std::vector<std::int64_t>& compact_of) {
  s.x = state.x_m, s.y = state.y_m, s.z = state.z_m;
  s.vx = state.vx_mps, s.vy = state.vy_mps, s.vz = state.vz_mps;
  compact_of.assign(topology.node_count(), -1);
  for (std::size_t j = 0; j < state.nodes.size(); ++j) compact_of[state.nodes[j]] = static_cast<std::int64_t>(j);
  s.facet_nodes.clear();
  for (std::uint32_t f : state.facets)
    for (int a = 0; a < 4; ++a) {
      const std::int64_t c = compact_of[topology.facet_nodes[4 * f + a]];
      if (c < 0)
        throw cosim::Error("surface of exchange " + std::to_string(state.exchange) + ": facet " + std::to_string(f) +
                           " has a node that was not sent");
      s.facet_nodes.push_back(static_cast<std::uint32_t>(c));
    }
  s.friction_coefficient = state.friction_coefficient;
  s.node_mass_kg.clear();
  if (topology.node_mass_kg.size() == topology.node_count())
    for (std::uint32_t node : state.nodes) s.node_mass_kg.push_back(topology.node_mass_kg[node]);
  s.facet_id.assign(state.facets.begin(), state.facets.end());
  s.closed_slit.resize(state.facets.size());
  for (std::size_t j = 0; j < state.facets.size(); ++j)
    s.closed_slit[j] = topology.facet_tags[state.facets[j]] == cosim::FacetTag::sipe_wall;
}

double particle_reach_z(std::size_t n, const double* z, const double* vz, const double* az, double window_s,
                        double particle_radius_m) {
  double top = -std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < n; ++i)
    top = std::max(top, z[i] + std::max(0.0, (vz[i] + az[i] * window_s) * window_s));
  return n == 0 ? top : top + 2.0 * particle_radius_m;
}

void sparse_surface_loads(const cosim::SurfaceState& state, const SurfaceContactResult& l, cosim::SurfaceLoads& out) {
  out.exchange = state.exchange, out.time_s = state.time_s;
  out.particle_reach_z_m = l.particle_reach_z_m;
  out.nodes.clear(), out.fx_N.clear(), out.fy_N.clear(), out.fz_N.clear();
  for (std::size_t j = 0; j < state.nodes.size(); ++j) {
    if (l.node_fx[j] == 0.0 && l.node_fy[j] == 0.0 && l.node_fz[j] == 0.0) continue;
    out.nodes.push_back(state.nodes[j]);
    out.fx_N.push_back(l.node_fx[j]), out.fy_N.push_back(l.node_fy[j]), out.fz_N.push_back(l.node_fz[j]);
  }
  out.facets.clear(), out.normal_force_N.clear(), out.tangential_x_N.clear(), out.tangential_y_N.clear();
  out.pressure_x_N.clear(), out.pressure_y_N.clear(), out.pressure_z_N.clear();
  out.tangential_z_N.clear(), out.contact_area_m2.clear(), out.pressure_Pa.clear();
  for (std::size_t f = 0; f < state.facets.size(); ++f) {
    if (l.particles_in_contact[f] == 0) continue;
    out.facets.push_back(state.facets[f]);
    out.normal_force_N.push_back(l.facet_normal_force_N[f]);
    out.pressure_x_N.push_back(l.facet_pressure_x_N[f]);
    out.pressure_y_N.push_back(l.facet_pressure_y_N[f]);
    out.pressure_z_N.push_back(l.facet_pressure_z_N[f]);
    out.tangential_x_N.push_back(l.facet_tangential_x_N[f]);
    out.tangential_y_N.push_back(l.facet_tangential_y_N[f]);
    out.tangential_z_N.push_back(l.facet_tangential_z_N[f]);
    out.contact_area_m2.push_back(l.facet_contact_area_m2[f]);
    out.pressure_Pa.push_back(l.facet_pressure_Pa[f]);
  }
}

double held_load_window_limit(const ContactSurface& surface, double stiffness_N_per_m, double spacing_m) {
  const std::size_t n = surface.x.size();
  if (surface.node_mass_kg.size() != n || !(stiffness_N_per_m > 0)) return std::numeric_limits<double>::infinity();
  std::vector<double> area(n, 0.0);
  for (std::size_t f = 0; f < surface.facet_count(); ++f) {
    const double quarter = 0.25 * facet_area_vector(surface, f).norm();
    for (int a = 0; a < 4; ++a) area[surface.facet_nodes[4 * f + a]] += quarter;
  }
  double limit = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < n; ++a)
    if (area[a] > 0 && surface.node_mass_kg[a] > 0)
      limit = std::min(limit, spacing_m * std::sqrt(2.0 * surface.node_mass_kg[a] / (stiffness_N_per_m * area[a])));
  return limit;
}

double surface_contact_stable_dt(double min_particle_mass_kg, double stiffness_N_per_m) {
  if (!(stiffness_N_per_m > 0)) return std::numeric_limits<double>::infinity();
  return 2.0 * std::sqrt(min_particle_mass_kg / stiffness_N_per_m);
}

void surface_contact(const ContactSurface& s, const SurfaceContactParameters& params, std::size_t n_particles,
                     const double* x, const double* y, const double* z, const double* vx, const double* vy,
                     const double* vz, const double* mass, double dt, double* ax, double* ay, double* az,
                     SurfaceContactResult& loads, FrictionHistory* history, const std::uint32_t* particle_id,
                     const std::uint8_t* drainable) {
  const std::size_t nn = s.x.size(), nf = s.facet_count();
  if (s.facet_nodes.size() != 4 * nf || s.friction_coefficient.size() != nf || s.y.size() != nn ||
      s.z.size() != nn || s.vx.size() != nn || s.vy.size() != nn || s.vz.size() != nn ||
      (!s.facet_id.empty() && s.facet_id.size() != nf))
    throw cosim::Error("contact surface: node or facet arrays differ in length");
  for (std::uint32_t n : s.facet_nodes)
    if (n >= nn) throw cosim::Error("contact surface: facet node " + std::to_string(n) + " out of range");
  loads = SurfaceContactResult{};
  loads.node_fx.assign(nn, 0.0), loads.node_fy.assign(nn, 0.0), loads.node_fz.assign(nn, 0.0);
  for (auto* v : {&loads.facet_normal_force_N, &loads.facet_pressure_x_N, &loads.facet_pressure_y_N,
                  &loads.facet_pressure_z_N, &loads.facet_tangential_x_N, &loads.facet_tangential_y_N,
                  &loads.facet_tangential_z_N, &loads.facet_contact_area_m2, &loads.facet_pressure_Pa})
    v->assign(nf, 0.0);
  loads.particles_in_contact.assign(nf, 0);
  auto id_of = [&](std::size_t i) { return particle_id ? particle_id[i] : static_cast<std::uint32_t>(i); };
  if (nf == 0 || n_particles == 0) {
    if (history) *history = FrictionHistory{};
    return;
  }

  const double radius = params.particle_radius_m, k = params.stiffness_N_per_m;
  const double depth = params.max_depth_m > 0 ? params.max_depth_m : 2.0 * radius;
  const double reach = std::max(radius, depth);
  // Unit outward normals and areas ((x2 - x0) x (x3 - x1) / 2, exact for a planar quad).
  std::vector<V3> normal(nf);
  std::vector<double> area(nf);
  auto node = [&](std::uint32_t n) { return V3(s.x[n], s.y[n], s.z[n]); };
  for (std::size_t f = 0; f < nf; ++f) {
    const V3 a = facet_area_vector(s, f);
    area[f] = a.norm();
    normal[f] = cosim::unit_normal(a);
  }
  const FacetGrid grid = bin_facets(s, reach);

  // Per-particle contact slots, kept between calls (a fresh 100k-particle
  // buffer cost 60 ms per call to allocate and clear).
  // (A reference, so that the OpenMP threads share the calling thread's buffer.)
  static thread_local std::vector<ParticleContacts> buffer;
  if (buffer.size() < n_particles) buffer.resize(n_particles);
  std::vector<ParticleContacts>& contacts = buffer;
  // The film between a facet (contact direction n, the particle at `gap` from
  // it along n) and each wall it faces, along the wall's normal through the
  // particle: the particle's distance to the wall plus the gap's projection.
  constexpr double kFacingCos = 0.70710678118;  // cos 45 deg
  const bool can_drain = drainable && params.drain_film_m > 0 && !params.walls.empty();
  auto pinched = [&](const V3& p, const V3& n, double gap) {
    for (const SurfaceContactParameters::Wall& w : params.walls) {
      const double facing = -w.inside_sign * n[w.axis];
      if (facing < kFacingCos) continue;
      const double to_wall = w.inside_sign * (p[w.axis] - w.position_m);
      if (to_wall + gap / facing < params.drain_film_m) return true;
    }
    return false;
  };
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
    // This particle's sticks of the last call (each can be taken over once).
    const FrictionHistory::Stick* old = nullptr;
    int old_count = 0;
    bool old_taken[kMaxContacts] = {false, false, false, false, false, false};
    if (history) {
      const std::uint32_t id = id_of(i);
      if (static_cast<std::size_t>(id) + 1 < history->begin.size()) {
        old = history->sticks.data() + history->begin[id];
        old_count = std::min<int>(kMaxContacts, static_cast<int>(history->begin[id + 1] - history->begin[id]));
      }
    }
    // Penalty force of one facet along `n` with penetration `delta`, friction
    // against the facet's velocity at the contact point (weights w).
    auto add_contact = [&](std::int32_t f, const V3& n, double delta, const double w[4]) {
      if (pc.count == kMaxContacts) return;
      const std::uint32_t* q = &s.facet_nodes[4 * f];
      V3 vs = V3::Zero();
      for (int a = 0; a < 4; ++a) vs += w[a] * V3(s.vx[q[a]], s.vy[q[a]], s.vz[q[a]]);
      const V3 rel = vp - vs;
      const double vn = rel.dot(n);
      // A particle pushed past the facet plane (penetration beyond its radius)
      // is pushed back with the force of a radius's penetration: no larger
      // impulse reaches the light tread nodes of a sipe-cut block.
      const double penetration = delta;
      delta = std::min(delta, radius);
      const double c_d = cosim::penalty::damping_coefficient(params.damping_ratio, k, m);
      const cosim::penalty::NormalForce normal =
          cosim::penalty::normal_force(k, delta, vn, c_d, cosim::penalty::Damping::approach_only);
      const double fn = normal.force_N;
      const V3 vt_vec = rel - vn * n;
      const std::uint32_t fid = s.facet_id.empty() ? static_cast<std::uint32_t>(f) : s.facet_id[f];
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
      V3 spring = V3::Zero();
      int from = -1;
      double best_cos = kStickInheritCos;
      for (int o = 0; o < old_count; ++o) {
        if (old_taken[o]) continue;
        if (old[o].facet == fid) {
          from = o;
          break;
        }
        const double c = n.dot(V3(old[o].normal[0], old[o].normal[1], old[o].normal[2]));
        if (c >= best_cos) best_cos = c, from = o;
      }
      if (from >= 0) {
        old_taken[from] = true;
        const V3 prev(old[from].force[0], old[from].force[1], old[from].force[2]);
        const V3 in_plane = prev - prev.dot(n) * n;
        const double norm = in_plane.norm();
        if (norm > 0.0) spring = in_plane * (prev.norm() / norm);
      }
      const double mu = s.friction_coefficient[f];
      const double kt = params.tangential_stiffness_ratio * k;
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
        const double c_t = cosim::penalty::damping_coefficient(params.damping_ratio, kt, m);
        ft = spring - c_t * vt_vec;
        const cosim::penalty::CoulombCap damped = cosim::penalty::coulomb_cap(ft.norm(), cap);
        if (damped.sliding) ft *= damped.scale;
        friction_J = std::max(0.0, -(ft - spring).dot(vt_vec)) * dt;
      }
      const double ft_mag = ft.norm();
      const V3 force = fn * n + ft;
      Contact& ct = pc.c[pc.count++];
      ct.facet = f;
      ct.facet_id = fid;
      for (int a = 0; a < 4; ++a) ct.w[a] = w[a];
      for (int a = 0; a < 3; ++a) ct.f[a] = force[a], ct.ft[a] = ft[a], ct.normal[a] = n[a], ct.spring[a] = spring[a];
      ct.fn = fn;
      ct.penetration_m = penetration;
      ct.friction_J = friction_J;
      ct.damping_J = cosim::penalty::approach_damping_power(normal, vn) * dt;
      ct.elastic_J = 0.5 * k * delta * delta + (ft_mag > 0.0 ? 0.5 * spring.squaredNorm() / kt : 0.0);
    };
    // Face contacts: every facet whose plane the particle penetrates with its
    // projection inside the facet. Summing them (not only the closest) keeps
    // the force a gradient of one potential in concave corners (a groove's
    // floor and walls), where switching between closest facets pumped energy.
    struct Face {
      std::int32_t facet;
      double delta, w[4];
    };
    Face faces[kMaxContacts];
    int face_count = 0;
    double best = std::numeric_limits<double>::infinity();
    std::int32_t best_facet = -1;
    double best_w[4] = {0, 0, 0, 0};
    V3 best_point = V3::Zero();
    for (std::uint32_t e = grid.begin[cell]; e < grid.begin[cell + 1]; ++e) {
      const std::uint32_t f = grid.entries[e];
      if (area[f] <= 0) continue;
      const std::uint32_t* q = &s.facet_nodes[4 * f];
      const V3 a = node(q[0]), b = node(q[1]), cc = node(q[2]), d = node(q[3]);
      const V3& n = normal[f];
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
          if (face_count < kMaxContacts) {
            Face& fc = faces[face_count++];
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
      if (std::min(d1, d2) < best) {
        best = std::min(d1, d2), best_facet = static_cast<std::int32_t>(f);
        if (d1 <= d2) best_w[0] = w1[0], best_w[1] = w1[1], best_w[2] = w1[2], best_w[3] = 0, best_point = p1;
        else best_w[0] = w2[0], best_w[1] = 0, best_w[2] = w2[1], best_w[3] = w2[2], best_point = p2;
      }
    }
    // A water particle squeezed against a wall below the film it resolves leaves
    // the flow (SurfaceContactParameters::drain_film_m) instead of being crushed.
    const bool edge = face_count == 0 && best_facet >= 0 && best < radius * radius;
    if (can_drain && drainable[i]) {
      bool squeezed = false;
      for (int a = 0; a < face_count && !squeezed; ++a)
        squeezed = pinched(p, normal[faces[a].facet], radius - faces[a].delta);
      if (edge && !squeezed) {
        const V3 offset = p - best_point;
        const double distance = std::sqrt(best);
        if (offset.dot(normal[best_facet]) > 0 && distance > 1e-12)
          squeezed = pinched(p, V3(offset / distance), distance);
      }
      if (squeezed) {
        pc.drained = true;
        return;
      }
    }
    // Neighbouring facets within 5 degrees of each other are one surface: a
    // particle on their shared edge (inside both, the edge included) or behind
    // both near a gentle convex edge is pushed once, by the deeper (then the
    // lower-numbered) facet. Facets at larger angles (a groove's floor and
    // wall) both push.
    for (int a = 0; a < face_count; ++a) {
      bool keep = true;
      for (int b = 0; b < face_count && keep; ++b) {
        if (a == b || normal[faces[a].facet].dot(normal[faces[b].facet]) < kSameSurfaceCos) continue;
        keep = faces[a].delta > faces[b].delta || (faces[a].delta == faces[b].delta && faces[a].facet < faces[b].facet);
      }
      if (keep) add_contact(faces[a].facet, normal[faces[a].facet], faces[a].delta, faces[a].w);
    }
    // Edge and corner contact (a convex ridge, e.g. a block's edge): no face
    // holds the particle's projection; the closest point pushes it away from
    // itself, along the line from that point to the particle.
    if (edge) {
      const V3 offset = p - best_point;
      const double distance = std::sqrt(best);
      if (offset.dot(normal[best_facet]) > 0 && distance > 1e-12)
        add_contact(best_facet, V3(offset / distance), radius - distance, best_w);
    }
    for (int k2 = 0; k2 < pc.count; ++k2) {
      const Contact& ct = pc.c[k2];
      ax[i] += ct.f[0] / m, ay[i] += ct.f[1] / m, az[i] += ct.f[2] / m;
    }
  });

  // Serial sums in particle order: the reaction on the facet nodes and facets.
  for (std::size_t i = 0; i < n_particles; ++i) {
    if (contacts[i].drained) loads.drained.push_back(static_cast<std::uint32_t>(i));
    bool behind = false;
    for (int k2 = 0; k2 < contacts[i].count; ++k2) {
      const Contact& ct = contacts[i].c[k2];
      const std::uint32_t* q = &s.facet_nodes[4 * ct.facet];
      for (int a = 0; a < 4; ++a) {
        loads.node_fx[q[a]] -= ct.w[a] * ct.f[0];
        loads.node_fy[q[a]] -= ct.w[a] * ct.f[1];
        loads.node_fz[q[a]] -= ct.w[a] * ct.f[2];
      }
      loads.facet_normal_force_N[ct.facet] += ct.fn;
      loads.facet_pressure_x_N[ct.facet] -= ct.fn * ct.normal[0];
      loads.facet_pressure_y_N[ct.facet] -= ct.fn * ct.normal[1];
      loads.facet_pressure_z_N[ct.facet] -= ct.fn * ct.normal[2];
      loads.facet_tangential_x_N[ct.facet] -= ct.ft[0];
      loads.facet_tangential_y_N[ct.facet] -= ct.ft[1];
      loads.facet_tangential_z_N[ct.facet] -= ct.ft[2];
      ++loads.particles_in_contact[ct.facet];
      loads.total_fx_N -= ct.f[0], loads.total_fy_N -= ct.f[1], loads.total_fz_N -= ct.f[2];
      loads.friction_dissipation_J += ct.friction_J;
      loads.damping_dissipation_J += ct.damping_J;
      loads.elastic_energy_J += ct.elastic_J;
      // The deepest contact as a max in this serial loop: the same for any thread count.
      behind = behind || ct.penetration_m > params.particle_radius_m;
      if (ct.penetration_m > loads.max_penetration_m) {
        loads.max_penetration_m = ct.penetration_m;
        loads.deepest_x_m = x[i], loads.deepest_y_m = y[i], loads.deepest_z_m = z[i];
        loads.deepest_facet = ct.facet_id;
      }
    }
    if (behind) ++loads.particles_behind_surface;
  }
  // The sticks of this call become the history of the next, grouped by particle id.
  if (history) {
    std::uint32_t max_id = 0;
    for (std::size_t i = 0; i < n_particles; ++i) max_id = std::max(max_id, id_of(i));
    FrictionHistory next;
    next.begin.assign(static_cast<std::size_t>(max_id) + 2, 0);
    for (std::size_t i = 0; i < n_particles; ++i) next.begin[id_of(i) + 1] = static_cast<std::uint32_t>(contacts[i].count);
    for (std::size_t k2 = 0; k2 + 1 < next.begin.size(); ++k2) next.begin[k2 + 1] += next.begin[k2];
    next.sticks.resize(next.begin.back());
    for (std::size_t i = 0; i < n_particles; ++i) {
      FrictionHistory::Stick* out = next.sticks.data() + next.begin[id_of(i)];
      for (int k2 = 0; k2 < contacts[i].count; ++k2) {
        const Contact& ct = contacts[i].c[k2];
        out[k2].facet = ct.facet_id;
        for (int a = 0; a < 3; ++a)
          out[k2].normal[a] = static_cast<float>(ct.normal[a]), out[k2].force[a] = ct.spring[a];
      }
    }
    *history = std::move(next);
  }
  // The touched part of each facet: a surface particle stands for the (2 r)^2 = dx^2
  // of terrain surface around it (particles on a lattice of spacing dx), shared
  // equally between the facets it touches, up to the facet's own area.
  const double patch = 4.0 * radius * radius;
  for (std::size_t i = 0; i < n_particles; ++i)
    for (int k2 = 0; k2 < contacts[i].count; ++k2)
      loads.facet_contact_area_m2[contacts[i].c[k2].facet] += patch / contacts[i].count;
  for (std::size_t f = 0; f < nf; ++f) {
    if (loads.particles_in_contact[f] == 0) continue;
    const double touched = std::min(loads.facet_contact_area_m2[f], area[f]);
    loads.facet_contact_area_m2[f] = touched;
    loads.facet_pressure_Pa[f] = touched > 0 ? loads.facet_normal_force_N[f] / touched : 0.0;
  }
}

}  // namespace snow_sph
