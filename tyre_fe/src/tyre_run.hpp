#pragma once
// The tyre under the run skeleton (cosim/participant.hpp), in three files by
// concern: the run (run.cpp: the participant's hooks, the terrain it joins,
// outputs, checkpoints), its procedure (tyre_procedure.cpp: the stage machine
// of the transfer check, loading and rolling, and the rim's drive in each) and
// its results (tyre_results.hpp: the stages' sums and what they report).
//
// initialize() inflates the axisymmetric model and builds the 3D one; then a
// step on a terrain (solver3d.hpp) is a coupled participant's
// (cosim_coupling/coupled_participant.hpp): before_exchange runs the stage
// machine up to the next step; at a coupling window's start the exchange sends
// the surface, computes the element forces while the terrain works and receives
// the loads; after_exchange adds the loads, integrates and does the stage's
// per-step work.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cosim/participant.hpp"
#include "cosim_coupling/coupled_participant.hpp"
#include "tyre_fe/hydroplaning.hpp"
#include "tyre_fe/model3d.hpp"
#include "tyre_fe/outputs.hpp"
#include "tyre_fe/run.hpp"
#include "tyre_fe/scene.hpp"
#include "tyre_fe/solver3d.hpp"
#include "tyre_results.hpp"

namespace tyre_fe {

// Mean radial position of every 3D copy of a cross-section node.
inline double mean_radius_of(const Mesh3D& mesh, const State3d& s, int section_node) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    if (mesh.node_source[i] == section_node) sum += radial_position(s, static_cast<int>(i)), ++n;
  return n ? sum / n : 0.0;
}
// Moves the tyre so that its lowest point is `height_m` (in the frame whose z = 0
// is the terrain's undisturbed surface, docs/coupling.md).
void lower_tyre_to(const Model3d& model, State3d& s, double height_m);

class TyreRun final : public cosim::coupling::CoupledParticipant {
 public:
  TyreRun(const cosim::LoadedScene& loaded, const RunOptions& options)
      : CoupledParticipant(options.terrain),
        port_(options.terrain),
        loaded_(loaded),
        scene_(loaded.message),
        t_(scene_.tyre()),
        options_(options) {}

  double initialize(cosim::RunRecord& record) override;
  double time_s() const override { return s_.time_s; }
  std::uint64_t steps() const override { return s_.step; }
  void output(cosim::RunRecord& record) override;
  void finalize(cosim::RunRecord& record) override;
  void plots(cosim::RunRecord& record) override;
  void plot_energy_split(cosim::RunRecord& record);
  std::string end_status() const override { return at_max_steps_ ? "stopped_at_max_steps" : "completed"; }
  // A mesh-only run has nothing to continue. On a terrain the checkpoints are
  // taken between coupling windows, at the exchanges its peers take theirs
  // (docs/reliability.md, "Coupled runs"); none before it has joined.
  bool can_checkpoint() const override { return !options_.mesh_only && !t_.mesh_only(); }
  void save(cosim::CheckpointWriter& out) const override;
  void restore(const cosim::CheckpointReader& in) override;
  std::optional<std::uint64_t> exchanges_completed() const override {
    if (!joined() || s_.terrain.substep != 0) return std::nullopt;
    return s_.terrain.exchange;
  }

 private:
  enum Stage { kTransferCheck, kLoading, kRolling, kDone };

  // The run (run.cpp).
  // On a terrain, at a coupling window's start.
  bool exchange_due() const override { return joined() && s_.terrain.substep == 0; }
  // Surface out, element forces, loads in.
  bool exchange() override;
  // The rest of the step, then the stage's per-step work.
  bool after_exchange(bool peers_go_on) override;
  // The cross-section inflated in the axisymmetric model, then the 3D state from it.
  void inflate_and_transfer(const CrossSection& section, const TyreSetup& setup);
  void open_series(cosim::RunRecord& record);
  void join_terrain();
  void rejoin_terrain(const cosim::CheckpointReader& in, double own_dt_s);
  void coupled_performance(nlohmann::json& summary, double wall_s);

  // The procedure (tyre_procedure.cpp).
  // The stage machine up to the next step; false when every stage is done.
  bool before_exchange() override;
  RimDrive drive_now() const;
  RimDrive rolling_drive(double tau_s) const;
  bool each_step();  // a stage's per-step work; true ends the stage early
  bool loading_step();
  bool rolling_step();
  void begin_stage();
  void begin_loading();
  void begin_rolling();
  void end_stage();
  void end_loading();
  void end_rolling();
  void stand_on_the_terrains_floor();
  // The tread has passed the water's end by one filter width of road: the
  // reading (which stops at the end) has all its samples, centred means included.
  bool past_the_water() const;
  WaterEnd water_end_now() const;
  // The hydroplaning reading of the rolling stage so far (hydroplaning_curve_ once written).
  void report_hydroplaning_now();

  // What the tyre stands on, for the names of its forces: the terrain of a
  // coupled run, the rigid road, or both (a road under the terrain).
  bool road_under_terrain() const { return port_ && scene_.coupling().rigid_road_under_terrain(); }
  GroundNames ground() const { return {port_ != nullptr, road_under_terrain()}; }
  // Loaded on the road alone, the terrain placed around the tyre at rest (thesis 4.2).
  bool loaded_before_terrain() const {
    return road_under_terrain() && scene_.coupling().place_terrain_around_loaded_tyre();
  }

  // The run's own clocks, stage and sums by name, for save and restore
  // (templates, so that saving reads a const run through the same lists).
  template <class Run> static auto run_fields(Run& r) {
    return std::vector<std::pair<std::string, decltype(&r.next_csv_s_)>>{
        {"next_csv_s", &r.next_csv_s_},
        {"stage.t0_s", &r.stage_t0_s_},
        {"stage.t_end_s", &r.stage_t_end_s_},
        {"transfer.max_kinetic_J", &r.transfer_.max_kinetic_J},
        {"transfer.growth_integral_m_s", &r.transfer_.growth_integral_m_s},
        {"transfer.growth_time_s", &r.transfer_.growth_time_s},
        {"transfer.growth_min_m", &r.transfer_.growth_min_m},
        {"transfer.growth_max_m", &r.transfer_.growth_max_m},
        {"loading.unloaded_radius_m", &r.loading_.unloaded_radius_m},
        {"loading.load_N", &r.loading_.load_N},
        {"loading.ramp_s", &r.loading_.ramp_s},
        {"loading.start_s", &r.loading_.start_s},
        {"loading.previous_kinetic_J", &r.loading_.previous_kinetic_J},
        {"loading.slow_since_s", &r.loading_.slow_since_s},
        {"rolling.spin_up_radius_m", &r.spin_up_radius_m_},
        {"rolling.window_start_s", &r.window_start_s_},
        {"rolling.window_length_s", &r.window_length_s_},
        {"window.start_x_m", &r.window_.start_x_m},
        {"window.start_angle_rad", &r.window_.start_angle_rad},
        {"window.ground_fx_N", &r.window_.ground_fx_N},
        {"window.ground_fz_N", &r.window_.ground_fz_N},
        {"window.rim_fx_N", &r.window_.rim_fx_N},
        {"window.rm2_Nm", &r.window_.rm2_Nm},
        {"window.rim_height_m", &r.window_.rim_height_m},
        {"window.spin_rad_per_s", &r.window_.spin_rad_per_s},
        {"window.road_fz_N", &r.window_.road_fz_N},
        {"window.road_area_m2", &r.window_.road_area_m2}};
  }
  template <class Run> static auto run_flags(Run& r) {
    return std::vector<std::pair<std::string, decltype(&r.stage_begun_)>>{
        {"stage.begun", &r.stage_begun_},      {"stage.done", &r.stage_done_},
        {"at_max_steps", &r.at_max_steps_},    {"loading.at_rest", &r.loading_.at_rest},
        {"window.started", &r.window_.started}, {"hydroplaning_curve", &r.hydroplaning_curve_},
        {"afloat", &r.afloat_}};
  }

  TerrainPort* port_;  // null on the rigid road alone
  const cosim::LoadedScene& loaded_;
  const cosim::scene::Scene& scene_;
  const cosim::scene::TyreModel& t_;
  RunOptions options_;
  cosim::RunRecord* record_ = nullptr;
  std::unique_ptr<Model3d> model_;
  State3d s_;
  std::unique_ptr<FrameWriter> frames_;
  std::vector<std::string> tyre_columns_;  // tyre.csv's
  cosim::CsvWriter* csv_ = nullptr;
  cosim::CsvWriter* road_csv_ = nullptr;  // a road under the terrain only
  bool stepping_ = false, at_max_steps_ = false;
  bool forces_computed_ = false;  // by this step's exchange
  double next_csv_s_ = 0.0, csv_interval_s_ = 0.0;
  std::uint64_t max_steps_ = 0;
  int centre_ = 0;         // the cross-section's tread centre node
  double centre_r0_m_ = 0.0;  // its radius in the reference (uninflated) section
  // The stage under way.
  Stage stage_ = kTransferCheck;
  bool stage_begun_ = false, stage_done_ = false;
  double stage_t0_s_ = 0.0, stage_t_end_s_ = 0.0;
  TransferCheckSums transfer_;
  LoadingState loading_;
  // Rolling: the spin-up's radius, the averaging window (its start and length) and its sums.
  double spin_up_radius_m_ = 0.0, window_start_s_ = 0.0, window_length_s_ = 0.0;
  RollingWindowSums window_;
  // A road under the terrain: the rolling stage's road force and water lift
  // against the speed, every step (hydroplaning.hpp).
  HydroplaningSamples hydroplaning_;
  bool hydroplaning_curve_ = false, afloat_ = false;
  // Coupled run.
  std::uint64_t coupled_from_step_ = 0;
  double coupled_from_wall_s_ = 0.0, exchange_s_ = 0.0;
};

}  // namespace tyre_fe
