// Conversions between topic structs and coupler inputs/outputs; see wire.hpp.
#include "coupler/wire.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "cosim/error.hpp"

namespace coupler {

FacetLoads facet_loads_from_contact(const cosim::transport::ContactLoads& c, const std::vector<FacetTag>& tags,
                                    const FacetGeometry& g) {
  const std::size_t n = c.facets.size();
  for (const auto* f : {&c.normal_force_N, &c.pressure_x_N, &c.pressure_y_N, &c.pressure_z_N, &c.tangential_x_N,
                        &c.tangential_y_N, &c.tangential_z_N, &c.contact_area_m2})
    if (f->size() != n)
      throw cosim::Error("ContactLoads: per-facet arrays differ in length from facets (" + std::to_string(n) + ")");
  if (g.area_m2.size() != tags.size())
    throw cosim::Error("ContactLoads: facet geometry covers " + std::to_string(g.area_m2.size()) + " facets, tags " +
                       std::to_string(tags.size()));
  FacetLoads l;
  for (auto* v : {&l.pressure_x_N, &l.pressure_y_N, &l.pressure_z_N, &l.friction_x_N, &l.friction_y_N,
                  &l.friction_z_N, &l.centroid_x_m, &l.centroid_y_m, &l.centroid_z_m, &l.contact_area_m2})
    v->resize(n);
  l.tag.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t f = c.facets[k];
    if (f >= tags.size())
      throw cosim::Error("ContactLoads: facet index " + std::to_string(f) + " (entry " + std::to_string(k) +
                         ") is out of range: the surface has " + std::to_string(tags.size()) + " facets");
    // The pressure part as the terrain summed it, contact by contact: at a block's
    // edge a particle pushes along the line from the edge to itself, which the
    // facet normal times the normal force would turn into the facet's direction.
    l.tag[k] = tags[f];
    l.pressure_x_N[k] = c.pressure_x_N[k], l.pressure_y_N[k] = c.pressure_y_N[k], l.pressure_z_N[k] = c.pressure_z_N[k];
    l.friction_x_N[k] = c.tangential_x_N[k], l.friction_y_N[k] = c.tangential_y_N[k];
    l.friction_z_N[k] = c.tangential_z_N[k];
    l.centroid_x_m[k] = g.centroid_x_m[f], l.centroid_y_m[k] = g.centroid_y_m[f];
    l.centroid_z_m[k] = g.centroid_z_m[f];
    l.contact_area_m2[k] = c.contact_area_m2[k];
  }
  return l;
}

void check_wheel_state(const cosim::transport::WheelState& w, const std::string& what) {
#define COSIM_NAMED_VALUE(type, name, init) {#name, w.name},
  const std::pair<const char*, double> fields[] = {COSIM_WIRE_FIELDS_WheelState(COSIM_NAMED_VALUE)};
#undef COSIM_NAMED_VALUE
  for (const auto& [name, value] : fields)
    if (!std::isfinite(value)) throw cosim::Error(what + ": " + name + " is not a finite number");
}

WheelInput wheel_input(const cosim::transport::WheelState& w, double rolling_radius_m) {
  WheelInput in;
  in.rim_x_m = w.rim_x_m;
  in.rim_z_m = w.rim_z_m;
  in.reaction_moment_y_Nm = w.reaction_moment_y_Nm;
  in.rolling_radius_m = rolling_radius_m;
  return in;
}

// Every field of the topic (cosim/wire_fields.hpp) from the decomposition's
// field of the same name.
cosim::transport::ForceSummary force_summary(const ForceDecomposition& d,
                                             const cosim::transport::SampleHeader& header) {
  cosim::transport::ForceSummary s;
  s.header = header;
#define COSIM_FROM_DECOMPOSITION(type, name, init) s.name = d.name;
  COSIM_WIRE_FIELDS_ForceSummary(COSIM_FROM_DECOMPOSITION)
#undef COSIM_FROM_DECOMPOSITION
  return s;
}

}  // namespace coupler
