// Force decomposition of thesis chapter 2; see forces.hpp and docs/force_decomposition.md.
#include "coupler/forces.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "cosim/error.hpp"

namespace coupler {

namespace {

std::size_t index(FacetTag t) { return static_cast<std::size_t>(t); }

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

}  // namespace

TagSet default_groove_tags() {
  TagSet g{};
  g[index(FacetTag::groove_wall)] = true;
  g[index(FacetTag::sipe_wall)] = true;
  return g;
}

TagSet pattern_recess_tags() {
  TagSet g = default_groove_tags();
  g[index(FacetTag::groove_bottom)] = true;
  return g;
}

TagSet tags_of(FacetTag tag) {
  TagSet g{};
  g[index(tag)] = true;
  return g;
}

void validate(const FacetLoads& l) {
  const std::size_t n = l.size();
  const std::vector<double>* fields[] = {&l.pressure_x_N, &l.pressure_y_N, &l.pressure_z_N, &l.friction_x_N,
                                         &l.friction_y_N, &l.friction_z_N, &l.centroid_x_m, &l.centroid_y_m,
                                         &l.centroid_z_m, &l.contact_area_m2};
  for (const auto* f : fields) {
    if (f->size() != n)
      throw cosim::Error("force decomposition: per-facet arrays differ in length (" + std::to_string(f->size()) +
                         " vs " + std::to_string(n) + " tags)");
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite((*f)[i]))
        throw cosim::Error("force decomposition: facet entry " + std::to_string(i) + " holds a non-finite value");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (index(l.tag[i]) >= cosim::kFacetTagCount)
      throw cosim::Error("force decomposition: facet entry " + std::to_string(i) + " has an invalid tag");
    if (l.contact_area_m2[i] < 0.0)
      throw cosim::Error("force decomposition: facet entry " + std::to_string(i) + " has a negative contact area");
  }
}

double traction_force(const FacetLoads& loads) { return sum(loads.friction_x_N); }

PressureSplit split_longitudinal_pressure(const FacetLoads& loads, const TagSet& groove_tags) {
  PressureSplit s;
  for (std::size_t i = 0; i < loads.size(); ++i) {
    if (groove_tags[index(loads.tag[i])])
      s.groove_force_N += loads.pressure_x_N[i];       // F2: aids travel when > 0
    else
      s.motion_resistance_N -= loads.pressure_x_N[i];  // F1: opposes travel when > 0
  }
  return s;
}

double vertical_pressure_force(const FacetLoads& loads) { return sum(loads.pressure_z_N); }

double vertical_pressure_force(const FacetLoads& loads, const TagSet& tags) {
  double f = 0.0;
  for (std::size_t i = 0; i < loads.size(); ++i)
    if (tags[index(loads.tag[i])]) f += loads.pressure_z_N[i];
  return f;
}

double decomposition_residual_N(const FacetLoads& loads, double total_x_N, double total_y_N, double total_z_N) {
  const double dx = sum(loads.pressure_x_N) + sum(loads.friction_x_N) - total_x_N;
  const double dy = sum(loads.pressure_y_N) + sum(loads.friction_y_N) - total_y_N;
  const double dz = sum(loads.pressure_z_N) + sum(loads.friction_z_N) - total_z_N;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double rolling_resistance_moment(const FacetLoads& loads, double rim_x_m) {
  double m = 0.0;
  for (std::size_t i = 0; i < loads.size(); ++i) m += loads.pressure_z_N[i] * (loads.centroid_x_m[i] - rim_x_m);
  return m;
}

double rolling_resistance_force(double rrm_Nm, double rolling_radius_m) {
  if (!(rolling_radius_m > 0.0) || !std::isfinite(rolling_radius_m))
    throw cosim::Error("force decomposition: rolling radius " + cosim::number_text(rolling_radius_m) +
                       " m must be > 0 (the zero-slip radius L / 2 pi of thesis eq. 5.1)");
  return rrm_Nm / rolling_radius_m;
}

double contact_area(const FacetLoads& loads) { return sum(loads.contact_area_m2); }

double contact_depth(const FacetLoads& loads, double terrain_surface_z_m) {
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < loads.size(); ++i)
    if (loads.contact_area_m2[i] > 0.0) lowest = std::fmin(lowest, loads.centroid_z_m[i]);
  return std::isfinite(lowest) ? terrain_surface_z_m - lowest : 0.0;
}

ForceDecomposition decompose_forces(const FacetLoads& loads, const WheelInput& wheel,
                                    const DecompositionOptions& options) {
  validate(loads);
  ForceDecomposition d;
  d.traction_force_N = traction_force(loads);
  const PressureSplit split = split_longitudinal_pressure(loads, options.groove_tags);
  d.motion_resistance_N = split.motion_resistance_N;
  d.groove_force_N = split.groove_force_N;
  d.vertical_pressure_force_N = vertical_pressure_force(loads);
  d.vertical_pressure_force_tread_top_N = vertical_pressure_force(loads, tags_of(FacetTag::tread_top));
  d.vertical_pressure_force_groove_N = vertical_pressure_force(loads, pattern_recess_tags());
  const double pressure_moment = rolling_resistance_moment(loads, wheel.rim_x_m);
  d.pressure_centre_offset_m = d.vertical_pressure_force_N != 0.0 ? pressure_moment / d.vertical_pressure_force_N : 0.0;
  d.rolling_resistance_moment_Nm =
      options.rrm_source == RrmSource::contact_pressure ? pressure_moment : wheel.reaction_moment_y_Nm;
  d.rolling_resistance_force_N = rolling_resistance_force(d.rolling_resistance_moment_Nm, wheel.rolling_radius_m);
  d.drawbar_pull_N = drawbar_pull(d.motion_resistance_N, d.groove_force_N, d.traction_force_N,
                                  d.rolling_resistance_force_N);
  d.net_longitudinal_pressure_force_N = net_longitudinal_pressure_force(d.motion_resistance_N, d.groove_force_N);
  d.traction_minus_rrf_N = d.traction_force_N - d.rolling_resistance_force_N;
  d.sinkage_m = options.sinkage == SinkageMeasure::contact_depth ? contact_depth(loads, options.terrain_surface_z_m)
                                                                 : options.reference_rim_z_m - wheel.rim_z_m;
  d.contact_area_m2 = contact_area(loads);
  return d;
}

}  // namespace coupler
