#include "cosim/surface_exchange.hpp"

#include <cmath>
#include <initializer_list>

#include "cosim/error.hpp"

namespace cosim {
namespace {

void check_length(std::size_t length, std::size_t expected, const std::string& what, const char* field,
                  const char* per) {
  if (length != expected)
    throw Error(what + ": " + field + " has " + std::to_string(length) + " entries for " + std::to_string(expected) +
                " " + per);
}

// Fields of `expected` entries each, checked in the order given (the first
// mismatch is the one reported).
struct NamedField {
  const std::vector<double>* values;
  const char* name;
};
void check_lengths(std::initializer_list<NamedField> fields, std::size_t expected, const std::string& what,
                   const char* per) {
  for (const NamedField& f : fields) check_length(f.values->size(), expected, what, f.name, per);
}

void check_range(const std::vector<std::uint32_t>& numbers, std::size_t count, const std::string& what,
                 const char* kind) {
  for (std::uint32_t n : numbers)
    if (n >= count)
      throw Error(what + ": " + kind + " " + std::to_string(n) + " does not exist (" + std::to_string(count) + " " +
                  kind + "s in the surface)");
}

// A NaN or an infinity from a peer would poison the receiving solver's state a
// step later under a vaguer message; refuse the sample here, naming the entry.
void check_finite(const std::vector<double>& values, const std::string& what, const char* field) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k]))
      throw Error(what + ": " + field + "[" + std::to_string(k) + "] is not a finite number");
}

}  // namespace

SurfaceLoadTotals totals(const SurfaceLoads& loads) {
  SurfaceLoadTotals t;
  for (std::size_t k = 0; k < loads.nodes.size(); ++k)
    t.force_N[0] += loads.fx_N[k], t.force_N[1] += loads.fy_N[k], t.force_N[2] += loads.fz_N[k];
  for (double a : loads.contact_area_m2) t.contact_area_m2 += a;
  return t;
}

void check_surface_topology(const SurfaceTopology& t, const std::string& what) {
  const std::size_t n = t.node_count();
  check_length(t.y_m.size(), n, what, "y_m", "nodes");
  check_length(t.z_m.size(), n, what, "z_m", "nodes");
  if (!t.node_mass_kg.empty()) check_length(t.node_mass_kg.size(), n, what, "node_mass_kg", "nodes");
  check_length(t.facet_nodes.size(), 4 * t.facet_count(), what, "facet_nodes", "(4 per facet) facet corners");
  check_range(t.facet_nodes, n, what, "surface node");
  check_finite(t.x_m, what, "x_m"), check_finite(t.y_m, what, "y_m"), check_finite(t.z_m, what, "z_m");
  for (std::size_t k = 0; k < t.node_mass_kg.size(); ++k)
    if (!(t.node_mass_kg[k] > 0.0 && std::isfinite(t.node_mass_kg[k])))
      throw Error(what + ": node_mass_kg[" + std::to_string(k) + "] is not a positive finite mass");
  for (std::size_t f = 0; f < t.facet_tags.size(); ++f)
    if (static_cast<int>(t.facet_tags[f]) >= kFacetTagCount)  // an unsigned byte: never below 0
      throw Error(what + ": facet_tags[" + std::to_string(f) + "] is not a facet tag");
}

void check_surface_state(const SurfaceState& s, const SurfaceTopology& topology, const std::string& what,
                         bool friction_required) {
  const std::size_t n = s.nodes.size(), facets = s.facets.size();
  check_lengths({{&s.x_m, "x_m"}, {&s.y_m, "y_m"}, {&s.z_m, "z_m"}, {&s.vx_mps, "vx_mps"}, {&s.vy_mps, "vy_mps"},
                 {&s.vz_mps, "vz_mps"}},
                n, what, "nodes");
  if (friction_required || !s.friction_coefficient.empty()) check_length(s.friction_coefficient.size(), facets, what, "friction_coefficient", "facets");
  check_range(s.nodes, topology.node_count(), what, "surface node");
  check_range(s.facets, topology.facet_count(), what, "surface facet");
  if (!std::isfinite(s.time_s)) throw Error(what + ": time_s is not a finite number");
  check_finite(s.x_m, what, "x_m"), check_finite(s.y_m, what, "y_m"), check_finite(s.z_m, what, "z_m");
  check_finite(s.vx_mps, what, "vx_mps"), check_finite(s.vy_mps, what, "vy_mps"), check_finite(s.vz_mps, what, "vz_mps");
  for (std::size_t k = 0; k < s.friction_coefficient.size(); ++k)
    if (!(s.friction_coefficient[k] >= 0.0 && std::isfinite(s.friction_coefficient[k])))
      throw Error(what + ": friction_coefficient[" + std::to_string(k) + "] is not a coefficient (finite, >= 0)");
}

void check_surface_loads(const SurfaceLoads& l, const SurfaceTopology& topology, const std::string& what) {
  const std::size_t n = l.nodes.size(), facets = l.facets.size();
  check_lengths({{&l.fx_N, "fx_N"}, {&l.fy_N, "fy_N"}, {&l.fz_N, "fz_N"}}, n, what, "nodes");
  check_lengths({{&l.normal_force_N, "normal_force_N"}, {&l.pressure_x_N, "pressure_x_N"},
                 {&l.pressure_y_N, "pressure_y_N"}, {&l.pressure_z_N, "pressure_z_N"},
                 {&l.tangential_x_N, "tangential_x_N"}, {&l.tangential_y_N, "tangential_y_N"},
                 {&l.tangential_z_N, "tangential_z_N"}, {&l.contact_area_m2, "contact_area_m2"},
                 {&l.pressure_Pa, "pressure_Pa"}},
                facets, what, "facets");
  check_range(l.nodes, topology.node_count(), what, "surface node");
  check_range(l.facets, topology.facet_count(), what, "surface facet");
  if (!std::isfinite(l.time_s)) throw Error(what + ": time_s is not a finite number");
  for (const auto* v : {&l.fx_N, &l.fy_N, &l.fz_N, &l.normal_force_N, &l.pressure_x_N, &l.pressure_y_N,
                        &l.pressure_z_N, &l.tangential_x_N, &l.tangential_y_N, &l.tangential_z_N,
                        &l.contact_area_m2, &l.pressure_Pa})
    check_finite(*v, what, "a force, area or pressure");
  if (!std::isfinite(l.particle_reach_z_m)) throw Error(what + ": particle_reach_z_m is not a finite number");
}

}  // namespace cosim
