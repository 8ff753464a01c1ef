// The coupled surface in and its loads out: the surface assembled from the
// owner's state, the sparse loads sent back, and the limits the exchange
// must respect (the held-load window, the contact's stable step).
#include <algorithm>
#include <cmath>
#include <limits>

#include "cosim/error.hpp"
#include "snow_sph/facet_grid.hpp"
#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

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

}  // namespace snow_sph
