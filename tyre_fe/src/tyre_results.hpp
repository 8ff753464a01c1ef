#pragma once
// The tyre run's results (tyre_run.hpp): the sums each stage of the procedure
// keeps over its steps, as fields with names, and what they give in
// summary.json's "results" (string-keyed there: that is the output format,
// docs/tyre_fe.md lists the keys).
#include <algorithm>
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/participant.hpp"
#include "tyre_fe/hydroplaning.hpp"
#include "tyre_fe/solver3d.hpp"

namespace tyre_fe {

// Forces of the ground on the tyre: the rigid road's and a terrain solver's loads.
inline double ground_fx(const State3d& s) { return s.road.force_x_N + s.terrain.load_totals.force_N[0]; }
inline double ground_fy(const State3d& s) { return s.road.force_y_N + s.terrain.load_totals.force_N[1]; }
inline double ground_fz(const State3d& s) { return s.road.force_z_N + s.terrain.load_totals.force_N[2]; }
inline double ground_area(const State3d& s) { return s.road.contact_area_m2 + s.terrain.load_totals.contact_area_m2; }

// What the tyre stands on names its forces: the terrain of a coupled run
// ("terrain_"), the rigid road ("road_"), or both ("ground_": a road under the terrain).
struct GroundNames {
  bool on_terrain = false, road_under_terrain = false;
  std::string operator()(const char* quantity) const {
    return std::string(road_under_terrain ? "ground_" : on_terrain ? "terrain_" : "road_") + quantity;
  }
};

// The check at rest after the transfer: the kinetic energy the revolved tyre
// picks up, and its crown's growth over the check. The tyre breathes about its
// 3D equilibrium undamped, so the growth's time mean is the equilibrium's.
struct TransferCheckSums {
  double max_kinetic_J = 0.0;
  double growth_integral_m_s = 0.0;  // time integral of the crown growth
  double growth_time_s = 0.0;        // the time it spans
  double growth_min_m = 1e30, growth_max_m = -1e30;
  void add_kinetic(double kinetic_J) { max_kinetic_J = std::max(max_kinetic_J, kinetic_J); }
  // Inline, and apart from add_kinetic, as the step's arithmetic was compiled
  // before: the compiler pairs the two sums' additions and leaves the product
  // unfused, which a fused multiply-add would change in the last bit.
  void add_growth(double growth_m, double dt_s) {
    growth_integral_m_s += growth_m * dt_s, growth_time_s += dt_s;
    growth_min_m = std::min(growth_min_m, growth_m), growth_max_m = std::max(growth_max_m, growth_m);
  }
};
// `growth_end_m`: the crown growth at the check's end.
void transfer_check_results(const TransferCheckSums& sums, double growth_end_m, const Energies& energy,
                            nlohmann::json& results);

// The loading stage: the load ramped in, and whether the tyre came to rest under it.
struct LoadingState {
  double unloaded_radius_m = 0.0;  // the lowest point below the rim before loading
  double load_N = 0.0, ramp_s = 0.0, start_s = 0.0;
  double previous_kinetic_J = 0.0;  // kinetic damping: the energy of the step before
  double slow_since_s = 0.0;        // the rim's speed below the rest speed since this time
  bool at_rest = false;
};
// The loaded tyre: its radii, deflection, contact and forces.
void loading_results(const LoadingState& loading, const State3d& s, const GroundNames& ground, nlohmann::json& results);

// The rolling stage's averaging window: sums over its steps (a mean is sum / steps).
struct RollingWindowSums {
  bool started = false;
  long steps = 0;
  double start_x_m = 0.0, start_angle_rad = 0.0;  // the rim at the window's start
  double ground_fx_N = 0.0, ground_fz_N = 0.0;
  double rim_fx_N = 0.0;        // the tyre's force on the rim along x
  double rm2_Nm = 0.0;          // the rim's moment
  double rim_height_m = 0.0;    // the rim above the road
  double spin_rad_per_s = 0.0;  // the rim's spin rate
  double road_fz_N = 0.0, road_area_m2 = 0.0;  // a road under the terrain
  void add(const State3d& s);
};
// The window's means and the rolled distance, the energy balance at the end.
void rolling_results(const RollingWindowSums& window, const State3d& s, const GroundNames& ground,
                     nlohmann::json& results);

// A road under the terrain: where the water ends along x (infinite: no terrain
// blocks) and how far ahead of the rim the tread meets the water's surface.
struct WaterEnd {
  double x_m = 0.0, tread_lead_m = 0.0;
};
// `rim_above_road_m`: the rim's height above the road (the loaded radius).
WaterEnd water_end(const cosim::scene::Scene& scene, double unloaded_radius_m, double rim_above_road_m,
                   double road_height_m);
// The road's share of the load against the speed (road_share_vs_speed.csv, a
// row every csv_interval_s) and the speeds where it falls below 50, 25 and 10 %
// (results "hydroplaning"); false if fewer than two samples were over the water.
bool report_hydroplaning(const HydroplaningSamples& samples, double load_N, double rim_x_m, const WaterEnd& end,
                         bool afloat, double csv_interval_s, cosim::RunRecord& record);

// The energies of summary.json, with the balance's definition.
nlohmann::json energy_json(const Energies& e);

}  // namespace tyre_fe
