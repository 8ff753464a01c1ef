#pragma once
// One exchange's force decomposition (thesis ch. 2, coupler/forces.hpp) from
// what crossed the coupler: the tyre's surface (the positions of the nodes the
// exchange lists), the wheel and the terrain's loads; and forces.csv, the row
// the coupler writes per exchange.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/checkpoint.hpp"
#include "coupler/forces.hpp"
#include "cosim/surface_exchange.hpp"
#include "cosim_transport/topics.hpp"

namespace coupler {

// Every surface node where the last exchange that listed it put it (an exchange
// lists only the nodes near the terrain).
struct SurfacePositions {
  std::vector<double> x_m, y_m, z_m;
  void update(const cosim::transport::SurfaceKinematics& k);
  // "<prefix>x_m", "<prefix>y_m", "<prefix>z_m"; restore keeps the node count.
  void save(cosim::CheckpointWriter& out, const std::string& prefix) const;
  void restore(const cosim::CheckpointReader& in, const std::string& prefix);
};

struct ExchangeForces {
  ForceDecomposition d;
  FacetLoads facet_loads;  // per contacted facet
  double total_x_N = 0.0, total_y_N = 0.0, total_z_N = 0.0;  // the loads on the tyre's nodes, summed
  double total_N = 0.0;                                      // |total|
  // The facets' pressure and friction parts against the total: they add up (decomposition_residual_N).
  double residual_N = 0.0;
};

// The decomposition from the current facet geometry of `surface` (topology: the
// facets' nodes and tags), the wheel (with r of eq. 5.1) and the terrain's loads.
ExchangeForces decompose_exchange(const SurfacePositions& surface, const cosim::SurfaceTopology& topology,
                                  const cosim::transport::WheelState& wheel,
                                  const cosim::transport::ContactLoads& loads, double rolling_radius_m,
                                  const DecompositionOptions& options);

// Over the run: the largest residual and the largest total force, the residual's scale.
struct ResidualWatch {
  double largest_residual_N = 0.0, largest_force_N = 0.0;
  void add(const ExchangeForces& f);
  // decomposition_residual_max_N and _relative (to the largest force; 0 before any force).
  void put_results(nlohmann::json& results) const;
};

// forces.csv: its columns, and the row of one exchange.
const std::vector<std::string>& forces_csv_columns();
std::vector<double> forces_csv_row(double time_s, std::uint64_t step, const ExchangeForces& f,
                                   const cosim::transport::WheelState& wheel);

}  // namespace coupler
