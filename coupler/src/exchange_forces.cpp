// One exchange's force decomposition and forces.csv; see exchange_forces.hpp.
#include "coupler/exchange_forces.hpp"

#include <algorithm>
#include <cmath>

#include "coupler/facet_geometry.hpp"
#include "coupler/wire.hpp"

namespace coupler {

namespace tp = cosim::transport;

void SurfacePositions::update(const tp::SurfaceKinematics& k) {
  for (std::size_t j = 0; j < k.nodes.size(); ++j) {
    const auto n = k.nodes[j];
    x_m[n] = k.x_m[j], y_m[n] = k.y_m[j], z_m[n] = k.z_m[j];
  }
}

void SurfacePositions::save(cosim::CheckpointWriter& out, const std::string& prefix) const {
  out.put(prefix + "x_m", x_m);
  out.put(prefix + "y_m", y_m);
  out.put(prefix + "z_m", z_m);
}

void SurfacePositions::restore(const cosim::CheckpointReader& in, const std::string& prefix) {
  x_m = in.get<double>(prefix + "x_m", x_m.size());
  y_m = in.get<double>(prefix + "y_m", y_m.size());
  z_m = in.get<double>(prefix + "z_m", z_m.size());
}

ExchangeForces decompose_exchange(const SurfacePositions& surface, const cosim::SurfaceTopology& topology,
                                  const tp::WheelState& wheel, const tp::ContactLoads& loads, double rolling_radius_m,
                                  const DecompositionOptions& options) {
  ExchangeForces f;
  const FacetGeometry geometry = quad_facet_geometry(surface.x_m, surface.y_m, surface.z_m, topology.facet_nodes);
  f.facet_loads = facet_loads_from_contact(loads, topology.facet_tags, geometry);
  f.d = decompose_forces(f.facet_loads, wheel_input(wheel, rolling_radius_m), options);
  double fx = 0.0, fy = 0.0, fz = 0.0;
  for (std::size_t j = 0; j < loads.nodes.size(); ++j) fx += loads.fx_N[j], fy += loads.fy_N[j], fz += loads.fz_N[j];
  f.total_x_N = fx, f.total_y_N = fy, f.total_z_N = fz;
  f.residual_N = decomposition_residual_N(f.facet_loads, fx, fy, fz);
  f.total_N = std::sqrt(fx * fx + fy * fy + fz * fz);
  return f;
}

void ResidualWatch::add(const ExchangeForces& f) {
  largest_residual_N = std::max(largest_residual_N, f.residual_N);
  largest_force_N = std::max(largest_force_N, f.total_N);
}

void ResidualWatch::put_results(nlohmann::json& results) const {
  results["decomposition_residual_max_N"] = largest_residual_N;
  results["decomposition_residual_relative"] = largest_force_N > 0 ? largest_residual_N / largest_force_N : 0.0;
}

const std::vector<std::string>& forces_csv_columns() {
  static const std::vector<std::string> columns = {
      "time_s", "step", "traction_force_N", "motion_resistance_N", "groove_force_N", "vertical_pressure_force_N",
      "rolling_resistance_moment_Nm", "rolling_resistance_force_N", "drawbar_pull_N",
      "net_longitudinal_pressure_force_N", "traction_minus_rrf_N", "sinkage_m", "contact_area_m2", "rim_x_m",
      "rim_z_m", "spin_rate_rad_per_s", "applied_torque_Nm", "rm2_Nm", "contact_force_x_N", "contact_force_z_N",
      "rim_longitudinal_force_N", "vertical_pressure_force_tread_top_N", "vertical_pressure_force_groove_N"};
  return columns;
}

std::vector<double> forces_csv_row(double time_s, std::uint64_t step, const ExchangeForces& f,
                                   const tp::WheelState& wheel) {
  const ForceDecomposition& d = f.d;
  return {time_s, double(step), d.traction_force_N, d.motion_resistance_N, d.groove_force_N,
          d.vertical_pressure_force_N, d.rolling_resistance_moment_Nm, d.rolling_resistance_force_N,
          d.drawbar_pull_N, d.net_longitudinal_pressure_force_N, d.traction_minus_rrf_N, d.sinkage_m,
          d.contact_area_m2, wheel.rim_x_m, wheel.rim_z_m, wheel.spin_rate_radps, wheel.applied_torque_Nm,
          wheel.reaction_moment_y_Nm, f.total_x_N, f.total_z_N, wheel.rim_longitudinal_force_N,
          d.vertical_pressure_force_tread_top_N, d.vertical_pressure_force_groove_N};
}

}  // namespace coupler
