#include "tyre_fe/run.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <optional>
#include <cstdio>
#include <memory>
#include <vector>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/ramp.hpp"
#include "cosim/signal.hpp"
#include "cosim/parallel.hpp"
#include "cosim/participant.hpp"
#include "tyre_fe/model3d.hpp"
#include "tyre_fe/hydroplaning.hpp"
#include "tyre_fe/outputs.hpp"
#include "tyre_fe/scene.hpp"
#include "tyre_fe/solver3d.hpp"
#include "tyre_fe/state_checkpoint.hpp"
#include "tyre_fe/tread_block.hpp"

namespace tyre_fe {
namespace sc = cosim::scene;
namespace {

// Mean radial position of every 3D copy of a cross-section node.
double mean_radius_of(const Mesh3D& mesh, const State3d& s, int section_node) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    if (mesh.node_source[i] == section_node) sum += radial_position(s, static_cast<int>(i)), ++n;
  return n ? sum / n : 0.0;
}

// Lowest point of the outer surface relative to the rim node: the unloaded radius.
double free_radius(const Model3d& m, const State3d& s) { return s.rim.z - lowest_contact_z(m, s); }

// The wheel load, speed and drive torque ramp in with zero rate at both ends.
double smooth_ramp(double t, double ramp) { return cosim::ramp(cosim::RampCurve::smoothstep, t, ramp); }

nlohmann::json energy_json(const Energies& e) {
  return {{"kinetic_J", e.kinetic_J},           {"internal_J", e.internal_J},
          {"hourglass_J", e.hourglass_J},       {"external_work_J", e.external_work_J},
          {"damping_work_J", e.damping_work_J}, {"contact_work_J", e.contact_work_J},
          {"initial_J", e.initial_J},           {"relative_error", e.balance_error()},
          {"note", "balance = KE + IE - E0 - W_ext - W_damping - W_contact, relative to max(IE, KE, |W_ext|)"}};
}

// The tyre under the run skeleton (cosim/participant.hpp): axisymmetric
// inflation and the 3D model in initialize(), then three stages of steps:
// a check at rest after the transfer, loading onto the road or the terrain,
// rolling. A step on a terrain (solver3d.hpp) is a coupled participant's
// (cosim_coupling/coupled_participant.hpp): before_exchange runs the stage
// machine up to the next step; at a coupling window's start the exchange sends
// the surface, computes the element forces while the terrain works and receives
// the loads; after_exchange adds the loads, integrates and does the stage's
// per-step work.
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
  void plots(cosim::RunRecord& record) override {
    if (stepping_) write_plots(record.out_dir());
    if (hydroplaning_curve_) {
      const double tenth = kHydroplaningRoadShare * load_;
      record.plot("road_share_vs_speed.csv", "road_force_vs_speed.png", 2,
                  {{3, "road force on the tyre"}, {4, "water lift on the tyre"}},
                  scene_.name() + ": road force against speed (" + cosim::number_text(1e3 * kHydroplaningFilter_s) +
                      " ms mean)",
                  "forward speed [m/s]", "vertical force [N]",
                  "set arrow from graph 0, first " + cosim::number_text(tenth) + " to graph 1, first " +
                      cosim::number_text(tenth) + " nohead dt 2 lc rgb 'gray40'\n");
    }
  }
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
  // The stage machine up to the next step; false when every stage is done.
  bool before_exchange() override;
  // On a terrain, at a coupling window's start.
  bool exchange_due() const override { return joined() && s_.terrain.substep == 0; }
  // Surface out, element forces, loads in.
  bool exchange() override;
  // The rest of the step, then the stage's per-step work.
  bool after_exchange(bool peers_go_on) override;
  RimDrive drive_now() const;
  bool each_step();  // a stage's per-step work; true ends the stage early
  void begin_stage();
  void end_stage();
  // A road under the terrain: the road's share of the load against the speed
  // (road_share_vs_speed.csv) and the speeds where it falls below 50, 25 and 10 %.
  void report_hydroplaning(nlohmann::json& results);
  void rejoin_terrain(const cosim::CheckpointReader& in, double own_dt_s);
  // Where the water ends along x (infinite: no terrain blocks) and how far
  // ahead of the rim the tread meets the water surface.
  struct WaterEnd {
    double x_m = 0.0, tread_lead_m = 0.0;
  };
  WaterEnd water_end() const;
  // The tread has passed the water's end by one filter width of road: the
  // reading (which stops at the end) has all its samples, centred means included.
  bool past_the_water() const;
  void join_terrain();
  // Forces of the ground on the tyre: the rigid road, or a terrain solver's loads.
  double ground_fx() const { return s_.road.force_x_N + s_.terrain.load_totals.force_N[0]; }
  double ground_fy() const { return s_.road.force_y_N + s_.terrain.load_totals.force_N[1]; }
  double ground_fz() const { return s_.road.force_z_N + s_.terrain.load_totals.force_N[2]; }
  // What the tyre stands on, for the names of its forces: the terrain of a
  // coupled run, the rigid road, or both ("ground_": a road under the terrain).
  bool road_under_terrain() const { return port_ && scene_.coupling().rigid_road_under_terrain(); }
  // Loaded on the road alone, the terrain placed around the tyre at rest (thesis 4.2).
  bool loaded_before_terrain() const {
    return road_under_terrain() && scene_.coupling().place_terrain_around_loaded_tyre();
  }
  void stand_on_the_terrains_floor();
  std::string ground(const char* quantity) const {
    return std::string(road_under_terrain() ? "ground_" : port_ ? "terrain_" : "road_") + quantity;
  }
  double ground_area() const { return s_.road.contact_area_m2 + s_.terrain.load_totals.contact_area_m2; }

  // The run's own clocks and sums, in one list shared by save and restore.
  template <class Run> static auto run_doubles(Run& r) {
    return std::vector<decltype(&r.next_csv_)>{
        &r.next_csv_, &r.stage_t0_, &r.stage_t_end_, &r.max_kinetic_, &r.growth_integral_, &r.growth_time_,
        &r.growth_min_, &r.growth_max_, &r.radius0_, &r.load_, &r.load_ramp_, &r.loading_start_,
        &r.previous_kinetic_, &r.slow_since_, &r.spin_up_radius_, &r.t_window_, &r.average_window_, &r.x_w_, &r.a_w_,
        &r.fx_sum_, &r.rim_fx_sum_, &r.m_sum_, &r.fz_sum_, &r.h_sum_, &r.w_sum_, &r.road_fz_sum_, &r.road_area_sum_};
  }

  TerrainPort* port_;  // null on the rigid road alone
  const cosim::LoadedScene& loaded_;
  const sc::Scene& scene_;
  const sc::TyreModel& t_;
  RunOptions options_;
  cosim::RunRecord* record_ = nullptr;
  std::unique_ptr<Model3d> model_;
  State3d s_;
  std::unique_ptr<FrameWriter> frames_;
  cosim::CsvWriter* csv_ = nullptr;
  cosim::CsvWriter* road_csv_ = nullptr;  // a road under the terrain only
  bool stepping_ = false, at_max_steps_ = false;
  bool forces_computed_ = false;  // by this step's exchange
  double next_csv_ = 0.0, csv_interval_ = 0.0;
  std::uint64_t max_steps_ = 0;
  int centre_ = 0;
  double r0_ = 0.0;
  // The stage under way.
  Stage stage_ = kTransferCheck;
  bool stage_begun_ = false, stage_done_ = false;
  double stage_t0_ = 0.0, stage_t_end_ = 0.0;
  // Transfer check.
  double max_kinetic_ = 0.0;
  // Crown growth over the transfer check: time integral, least and largest [m].
  double growth_integral_ = 0.0, growth_time_ = 0.0, growth_min_ = 1e30, growth_max_ = -1e30;
  // Loading.
  double radius0_ = 0.0, load_ = 0.0, load_ramp_ = 0.0, loading_start_ = 0.0, previous_kinetic_ = 0.0;
  bool at_rest_ = false;
  double slow_since_ = 0.0;  // the rim's speed below the rest speed since this time
  // Rolling: the averaging window's sums.
  double spin_up_radius_ = 0.0, t_window_ = 0.0, average_window_ = 0.0;
  double x_w_ = 0, a_w_ = 0, fx_sum_ = 0, rim_fx_sum_ = 0, m_sum_ = 0, fz_sum_ = 0, h_sum_ = 0, w_sum_ = 0;
  double road_fz_sum_ = 0, road_area_sum_ = 0;  // a road under the terrain
  // A road under the terrain: the rolling stage's road force and water lift
  // against the speed, every step (hydroplaning.hpp).
  HydroplaningSamples hydroplaning_;
  bool hydroplaning_curve_ = false, afloat_ = false;
  long n_w_ = 0;
  bool in_window_ = false;
  // Coupled run.
  std::uint64_t coupled_from_step_ = 0;
  double coupled_from_wall_ = 0.0, exchange_s_ = 0.0;
};

double TyreRun::initialize(cosim::RunRecord& record) {
  record_ = &record;
  nlohmann::json& summary = record.summary();
  nlohmann::json& results = record.results();
  const std::string out = record.out_dir();
  const TyreSetup setup = tyre_setup(loaded_);
  summary["tyre_size"] = setup.size_designation;
  summary["materials_source"] = setup.materials_source;
  summary["bulk_to_shear_ratio"] = setup.bulk_to_shear_ratio;
  const CrossSection section = make_section(setup);
  Mesh3D mesh = revolve(section, setup.pattern);
  summary["cross_section"] = {{"nodes", section.nodes.size()}, {"elements", section.quads.size()}};
  int per_tag[cosim::kFacetTagCount] = {};
  for (const auto& f : mesh.facets) ++per_tag[static_cast<int>(f.tag)];
  nlohmann::json tags = nlohmann::json::object();
  for (SurfaceTag t : cosim::kAllFacetTags) tags[cosim::facet_tag_name(t)] = per_tag[static_cast<int>(t)];
  results["nodes"] = mesh.nodes.size();
  results["elements"] = mesh.hexes.size();
  results["facets"] = mesh.facets.size();
  results["facets_by_tag"] = tags;
  summary["elements"] = mesh.hexes.size();
  const bool mesh_only = options_.mesh_only || t_.mesh_only();
  if (options_.write_vtk || mesh_only) {
    write_cross_section_vtk(out + "/cross_section.vtk", section, section.nodes);
    write_mesh_vtk(out + "/mesh3d.vtk", mesh, mesh.nodes);
    write_facets_vtk(out + "/surface.vtk", mesh, mesh.nodes);
  }
  // The model (masses, stable step) is cheap to build: mesh-only runs report the step too.
  Model3dOptions mo;
  mo.time_step_safety = scene_.time().cfl() > 0 ? scene_.time().cfl() : 0.8;
  mo.mass_scaling_target_dt_s = t_.mass_scaling_target_dt_s();
  model_ = std::make_unique<Model3d>(build_model3d(std::move(mesh), setup.materials, section, mo));
  const Model3d& model = *model_;
  summary["time_step"] = {{"stable_dt_s", model.stable_dt_s},
                          {"unscaled_stable_dt_s", model.unscaled_dt_s},
                          {"controlling_region", region_name(model.mesh.hex_region[model.dt_controlling_element])},
                          {"mass_scaling_target_dt_s", mo.mass_scaling_target_dt_s},
                          {"physical_mass_kg", model.physical_mass_kg},
                          {"added_mass_kg", model.added_mass_kg},
                          {"added_mass_percent", 100.0 * model.added_mass_kg / model.physical_mass_kg}};
  for (int r = 0; r < kRegionCount; ++r)
    if (model.region_min_dt_s[r] > 0.0)
      summary["time_step"]["regions"][region_name(static_cast<Region>(r))] = {
          {"min_stable_dt_s", model.region_min_dt_s[r]}, {"added_mass_kg", model.region_added_mass_kg[r]}};
  if (mesh_only) {
    stage_ = kDone;
    return 0.0;
  }

  // 1. Inflation in the axisymmetric model.
  AxisymLoadCase inflation;
  inflation.pressure_Pa = t_.inflation_pressure_pa();
  inflation.fixed_nodes = section.rim_nodes;
  if (t_.stages().inflation_tolerance() > 0) inflation.tolerance = t_.stages().inflation_tolerance();
  if (!options_.quiet)
    std::fprintf(stderr, "[%s] inflating the cross-section to %.0f kPa\n", scene_.name().c_str(),
                 inflation.pressure_Pa / 1e3);
  const AxisymResult axi = solve_axisym(section, setup.materials, inflation);
  if (!axi.converged)
    throw cosim::Error("axisymmetric inflation did not come to rest in " + std::to_string(axi.steps) +
                       " steps (residual ratio " + cosim::number_text(axi.residual_ratio) + ")");
  centre_ = section.tread_centre_node;
  r0_ = section.nodes[centre_][0];
  results["axisym_radial_growth_m"] = axi.nodes[centre_][0] - r0_;
  results["axisym_steps"] = axi.steps;
  results["axisym_residual_ratio"] = axi.residual_ratio;
  write_cross_section_vtk(out + "/cross_section_inflated.vtk", section, axi.nodes);

  // 2. Revolve and transfer; the 3D model starts inflated and at rest.
  double dt = model.stable_dt_s;
  if (scene_.time().fixed_dt_s() > 0) {
    if (scene_.time().fixed_dt_s() > model.stable_dt_s)
      throw cosim::Error(loaded_.locator().child("time").where("fixed_dt_s") + ": fixed time step " +
                         cosim::number_text(scene_.time().fixed_dt_s()) + " s is above the stable limit " +
                         cosim::number_text(model.stable_dt_s) + " s");
    dt = scene_.time().fixed_dt_s();
  }
  s_ = make_state3d(model, revolve_positions(model.mesh, axi.nodes, axi.twist_rad), t_.rim().mass_kg(),
                    t_.rim().spin_inertia_kg_m2());
  s_.dt_s = dt;
  s_.pressure_Pa = t_.inflation_pressure_pa();
  csv_ = &record.series("tyre.csv", {"time_s", "stage", "rim_x_m", "rim_z_m", "rim_angle_rad", "rim_vx_m_per_s",
                                     "rim_vz_m_per_s", "rim_omega_rad_per_s", "rim_vertical_force_N", "rm2_Nm",
                                     ground("force_x_N"), ground("force_y_N"), ground("force_z_N"),
                                     "rim_longitudinal_force_N", "contact_area_m2",
                                     "kinetic_J", "internal_J", "hourglass_J", "external_work_J",
                                     "energy_balance_error", "crown_radial_growth_m"});
  // A road under the terrain: the road's force and area apart, and the terrain's lift.
  if (road_under_terrain())
    road_csv_ = &record.series("road.csv", {"time_s", "road_force_x_N", "road_force_z_N", "road_contact_area_m2",
                                            "terrain_force_x_N", "terrain_force_z_N", "rim_vx_m_per_s"});
  csv_interval_ = scene_.output().csv_interval_s();
  max_steps_ = scene_.time().max_steps();
  frames_ = std::make_unique<FrameWriter>(out, options_.write_vtk ? scene_.output().vtk_interval_s() : 0.0);
  stepping_ = true;
  return cosim::planned_end_time_s(scene_);  // transfer check, loading, rolling
}

void TyreRun::save(cosim::CheckpointWriter& out) const {
  save_state(s_, out);
  frames_->save(out);
  std::vector<double> d;
  for (const double* v : run_doubles(*this)) d.push_back(*v);
  out.put("run.doubles", d);
  out.put("run.counters", std::vector<std::uint64_t>{std::uint64_t(stage_), stage_begun_, stage_done_, at_rest_,
                                                     at_max_steps_, hydroplaning_curve_, afloat_, in_window_,
                                                     std::uint64_t(n_w_)});
  hydroplaning_.save(out);
  if (joined()) save_terrain_coupling(s_.terrain, coupling_window_s(), out);
}

void TyreRun::restore(const cosim::CheckpointReader& in) {
  const double own_dt = s_.dt_s;  // the step the tyre proposes when it joins a terrain
  restore_state(in, s_);
  frames_->restore(in);
  const auto d = in.get<double>("run.doubles", run_doubles(*this).size());
  std::size_t k = 0;
  for (double* v : run_doubles(*this)) *v = d[k++];
  const auto c = in.get<std::uint64_t>("run.counters", 9);
  if (c[0] > kDone) throw cosim::Error(in.path() + ": run.counters: stage " + std::to_string(c[0]) + " unknown");
  stage_ = static_cast<Stage>(c[0]);
  stage_begun_ = c[1], stage_done_ = c[2], at_rest_ = c[3], at_max_steps_ = c[4];
  hydroplaning_curve_ = c[5], afloat_ = c[6], in_window_ = c[7];
  n_w_ = static_cast<long>(c[8]);
  hydroplaning_.restore(in);
  if (port_ && in.has("coupling.exchange")) rejoin_terrain(in, own_dt);
}

// A restarted coupled run (docs/reliability.md): the surface the tyre offered
// when it joined, its place in the exchanges, and the handshake again, at the
// checkpoint's exchange; the coupler must agree the same window as before.
void TyreRun::rejoin_terrain(const cosim::CheckpointReader& in, double own_dt_s) {
  const double saved_dt = s_.dt_s;
  s_.terrain.surface = make_contact_surface(model_->mesh);
  const double saved_window = restore_terrain_coupling(in, s_.terrain);
  const int saved_substeps = s_.terrain.substeps;
  s_.dt_s = own_dt_s;
  const double window_s = connect_to_terrain(*port_, s_);
  if (window_s != saved_window || s_.terrain.substeps != saved_substeps || s_.dt_s != saved_dt)
    throw cosim::Error(in.path() + ": the coupling window agreed now (" + cosim::number_text(window_s) + " s, " +
                       std::to_string(s_.terrain.substeps) + " sub-steps) is not the checkpoint's (" +
                       cosim::number_text(saved_window) + " s, " + std::to_string(saved_substeps) + ")");
  s_.time_stages = true;
  joined_with_window(window_s);
  coupled_from_step_ = s_.step;
  coupled_from_wall_ = record_->wall_s();
}

bool TyreRun::before_exchange() {
  // Stages end when their time is up (or their per-step work says so); a step
  // limit ends every stage at once (their results are those of the state reached).
  while (stage_ != kDone) {
    if (!stage_begun_) begin_stage();
    const bool time_up = !(s_.time_s < stage_t_end_ - 0.5 * s_.dt_s);
    if (!time_up && !stage_done_ && !at_max_steps_) {
      if (max_steps_ > 0 && s_.step >= max_steps_) {
        at_max_steps_ = true;
        continue;
      }
      return true;
    }
    end_stage();
  }
  return false;
}

// The exchange, at a coupling window's start (docs/coupling.md): the surface
// at t_n goes out before the element forces, so that the terrain works on it
// meanwhile; its loads of t_n come back after them and are held over the window.
bool TyreRun::exchange() {
  exchange_with_terrain(*model_, s_, *port_, exchange_s_);
  forces_computed_ = true;
  return true;  // a terrain that is gone throws
}

bool TyreRun::after_exchange(bool) {
  const RimDrive drive = drive_now();
  if (joined()) {
    complete_step_on_terrain(*model_, s_, drive, forces_computed_);
    forces_computed_ = false;
  } else if (!step3d(*model_, s_, drive)) {
    throw cosim::Error(non_finite_message(*model_, s_));
  }
  stage_done_ = each_step();
  return true;
}

void TyreRun::output(cosim::RunRecord&) {
  if (s_.time_s >= next_csv_ || stage_done_) {
    csv_->row({s_.time_s, double(stage_), s_.rim.x, s_.rim.z, s_.rim.angle, s_.rim.vx, s_.rim.vz, s_.rim.omega,
               s_.rim.tyre_force_z_N, s_.rim.rm2_Nm, ground_fx(), ground_fy(), ground_fz(), s_.rim.tyre_force_x_N,
               ground_area(),
               s_.energy.kinetic_J, s_.energy.internal_J, s_.energy.hourglass_J, s_.energy.external_work_J,
               s_.energy.balance_error(), mean_radius_of(model_->mesh, s_, centre_) - r0_});
    if (road_csv_)
      road_csv_->row({s_.time_s, s_.road.force_x_N, s_.road.force_z_N, s_.road.contact_area_m2,
                      s_.terrain.load_totals.force_N[0], s_.terrain.load_totals.force_N[2], s_.rim.vx});
    next_csv_ = s_.time_s + csv_interval_;
  }
  frames_->maybe_write(*model_, s_);
}

void TyreRun::begin_stage() {
  stage_begun_ = true;
  stage_done_ = false;
  stage_t0_ = s_.time_s;
  const auto& st = t_.stages();
  const Model3d& model = *model_;
  nlohmann::json& results = record_->results();
  switch (stage_) {
    case kTransferCheck:  // 3. Check at rest after the transfer: no damping, rim held.
      stage_t_end_ = s_.time_s + st.transfer_check_s();
      break;
    case kLoading:  // 4. Loading onto the road or the terrain (dynamic relaxation).
      if (port_ && !loaded_before_terrain()) join_terrain();
      stage_t_end_ = s_.time_s + st.loading_s();
      if (st.loading_s() <= 0) break;
      if (loaded_before_terrain())
        stand_on_the_terrains_floor();
      else if (!port_)
        place_road(model, s_, t_.road().initial_gap_m(), t_.road().friction_coefficient(), t_.road().penalty_scale());
      radius0_ = free_radius(model, s_);
      s_.damping_per_s = st.loading_damping_per_s();
      load_ = t_.rim().wheel_load_n(), load_ramp_ = t_.rim().load_ramp_time_s();
      loading_start_ = s_.time_s;
      previous_kinetic_ = 0.0;
      at_rest_ = false;
      break;
    case kRolling: {  // 5. Rolling.
      if (loaded_before_terrain()) join_terrain();  // the water placed around the tyre at rest
      stage_t_end_ = s_.time_s + st.rolling_s();
      if (st.rolling_s() <= 0) break;
      average_window_ = st.average_last_s() > 0 ? st.average_last_s() : 0.5 * st.rolling_s();
      t_window_ = s_.time_s + st.rolling_s() - average_window_;
      // Effective rolling radius estimate R - deflection / 3 (a common estimate; Pacejka, Tire and Vehicle Dynamics, 2006).
      const double unloaded = results.value("unloaded_radius_m", free_radius(model, s_));
      spin_up_radius_ = unloaded - (unloaded - (s_.rim.z - s_.road.height_m)) / 3.0;
      break;
    }
    case kDone:
      break;
  }
}

// Moves the tyre so that its lowest point is `height_m` (in the frame whose z = 0
// is the terrain's undisturbed surface, docs/coupling.md).
static void lower_tyre_to(const Model3d& model, State3d& s, double height_m) {
  const double lift = height_m - lowest_contact_z(model, s);
  for (double& z : s.z) z += lift;
  s.rim.z += lift;
}

// Loading before the terrain is placed (coupling.place_terrain_around_loaded_tyre):
// the road at the terrain's floor, the tyre road.initial_gap_m above it.
void TyreRun::stand_on_the_terrains_floor() {
  const double floor_z = scene_.sph().container().min().z();
  lower_tyre_to(*model_, s_, floor_z + t_.road().initial_gap_m());
  set_road(s_, floor_z, t_.road().friction_coefficient(), t_.road().penalty_scale());
}

// The terrain's undisturbed surface is z = 0 (docs/coupling.md): lift the tyre
// so that its lowest point is initial_gap above it, then join the run. A tyre
// loaded before the terrain is placed joins where it stands.
void TyreRun::join_terrain() {
  const Model3d& model = *model_;
  const auto& c = scene_.coupling();
  if (!loaded_before_terrain()) {
    lower_tyre_to(model, s_, c.initial_gap_m());
    s_.road.height_m = 0.0;  // heights below are measured from the terrain surface
    if (c.rigid_road_under_terrain()) {
      // The road at the terrain's floor; heights are then measured from the road.
      set_road(s_, scene_.sph().container().min().z(), t_.road().friction_coefficient(), t_.road().penalty_scale());
    }
  }
  s_.terrain.surface = make_contact_surface(model, s_);
  s_.terrain.band_m = c.contact_band_m();
  if (!options_.quiet)
    std::fprintf(stderr, "[%s] joining the terrain and the coupler (%zu surface facets)\n", scene_.name().c_str(),
                 s_.terrain.surface.facet_count());
  // The coupler answers with the coupling window; the tyre fills it with
  // equal sub-steps no larger than its own stable step (one in the common-step scheme).
  const double window = connect_to_terrain(*port_, s_);
  s_.time_stages = true;  // the exchange's share of the wall time (summary "performance")
  joined_with_window(window);
  coupled_from_step_ = s_.step;
  coupled_from_wall_ = record_->wall_s();
  nlohmann::json& summary = record_->summary();
  summary["coupled_dt_s"] = s_.dt_s;
  summary["coupling_window_s"] = window;
  summary["tyre_substeps"] = s_.terrain.substeps;
  record_->results()["coupled_time_step_s"] = s_.dt_s;
}

RimDrive TyreRun::drive_now() const {
  const double tau = s_.time_s - stage_t0_;
  RimDrive d;
  const auto& rim = t_.rim();
  switch (stage_) {
    case kTransferCheck:
      d.hold_z = true;
      break;
    case kLoading:
      d.wheel_load_N = load_ * smooth_ramp(tau, load_ramp_);
      break;
    case kRolling:
      d.hold_x = false;
      d.forward_speed_m_per_s = rim.forward_speed_m_per_s() * smooth_ramp(tau, rim.speed_ramp_time_s());
      d.wheel_load_N = rim.wheel_load_n();
      if (rim.spin_case() == sc::RimSpec::kAngularVelocityRadPerS) {
        d.angular_velocity_rad_per_s = rim.angular_velocity_rad_per_s() * smooth_ramp(tau, rim.speed_ramp_time_s());
      } else if (tau < rim.speed_ramp_time_s()) {
        // Spin-up: while the speed ramps the spin follows it at the estimated free
        // rolling radius, so that the tyre starts rolling instead of sliding; then the
        // spin is released (free rolling) and the torque ramps in.
        d.angular_velocity_rad_per_s = d.forward_speed_m_per_s / spin_up_radius_;
      } else {
        d.spin_prescribed = false;
        d.drive_torque_Nm = rim.drive_torque_nm() * smooth_ramp(tau - rim.speed_ramp_time_s(), rim.torque_ramp_time_s());
      }
      break;
    case kDone:
      break;
  }
  return d;
}

bool TyreRun::each_step() {
  switch (stage_) {
    case kTransferCheck: {
      max_kinetic_ = std::max(max_kinetic_, s_.energy.kinetic_J);
      const double growth = mean_radius_of(model_->mesh, s_, centre_) - r0_;
      growth_integral_ += growth * s_.dt_s, growth_time_ += s_.dt_s;
      growth_min_ = std::min(growth_min_, growth), growth_max_ = std::max(growth_max_, growth);
      return false;
    }
    case kLoading: {
      const auto& st = t_.stages();
      if (st.loading_kinetic_damping()) {
        if (s_.energy.kinetic_J < previous_kinetic_) {
          zero_velocities(s_);
          previous_kinetic_ = 0.0;
        } else {
          previous_kinetic_ = s_.energy.kinetic_J;
        }
      }
      const double tol = st.loading_rest_tolerance();
      if (tol <= 0.0) return false;
      const bool balanced = s_.time_s - loading_start_ >= load_ramp_ && std::fabs(ground_fz() - load_) < tol * load_ &&
                            std::fabs(s_.rim.tyre_force_z_N - load_) < tol * load_ &&
                            s_.energy.kinetic_J < tol * s_.energy.internal_J;
      // The rim's speed must stay below the rest speed for the hold time (as a body's rest in snow_sph).
      const double rest_speed = st.loading_rest_speed_m_per_s();
      if (!(balanced && (rest_speed <= 0.0 || std::fabs(s_.rim.vz) < rest_speed))) slow_since_ = s_.time_s;
      at_rest_ = balanced && (rest_speed <= 0.0 || s_.time_s - slow_since_ >= st.loading_rest_hold_s());
      return at_rest_;
    }
    case kRolling:
      if (road_under_terrain()) {
        hydroplaning_.add(s_.time_s, s_.rim.vx, s_.road.force_z_N, s_.terrain.load_totals.force_N[2]);
        if (t_.stages().end_rolling_when_afloat() && hydroplaning_.afloat(load_)) {
          afloat_ = true;
          return true;
        }
        if (t_.stages().end_rolling_past_the_water() && past_the_water()) return true;
      }
      if (s_.time_s < t_window_) return false;
      if (!in_window_) x_w_ = s_.rim.x, a_w_ = s_.rim.angle, in_window_ = true;
      fx_sum_ += ground_fx(), m_sum_ += s_.rim.rm2_Nm, fz_sum_ += ground_fz(), ++n_w_;
      rim_fx_sum_ += s_.rim.tyre_force_x_N;
      road_fz_sum_ += s_.road.force_z_N, road_area_sum_ += s_.road.contact_area_m2;
      h_sum_ += s_.rim.z - s_.road.height_m, w_sum_ += s_.rim.omega;
      return false;
    case kDone:
      return false;
  }
  return false;
}

void TyreRun::end_stage() {
  const Model3d& model = *model_;
  const auto& st = t_.stages();
  nlohmann::json& results = record_->results();
  switch (stage_) {
    case kTransferCheck: {
      // The transferred tyre is not exactly in 3D equilibrium (the one-point hex
      // against the axisymmetric quad, docs/tyre_fe.md) and breathes about it
      // undamped: the crown radius at the check's end depends on where in that
      // swing the check ends (0.714-0.824 mm over 12 ms on the shipped scene).
      // Its time mean over the check is the 3D equilibrium's growth.
      results["radial_growth_3d_end_m"] = mean_radius_of(model.mesh, s_, centre_) - r0_;
      results["radial_growth_3d_m"] =
          growth_time_ > 0.0 ? growth_integral_ / growth_time_ : results["radial_growth_3d_end_m"].get<double>();
      if (growth_time_ > 0.0) results["radial_growth_3d_swing_m"] = {growth_min_, growth_max_};
      results["kinetic_energy_after_transfer_J"] = s_.energy.kinetic_J;
      results["max_kinetic_energy_after_transfer_J"] = max_kinetic_;
      results["internal_energy_after_transfer_J"] = s_.energy.internal_J;
      const double growth_axi = results["axisym_radial_growth_m"].get<double>();
      results["radial_growth_difference_percent"] =
          growth_axi != 0.0 ? 100.0 * (results["radial_growth_3d_m"].get<double>() - growth_axi) / growth_axi : 0.0;
      break;
    }
    case kLoading: {
      if (st.loading_s() <= 0) break;
      results["loading_time_s"] = s_.time_s - loading_start_;
      results["loading_came_to_rest"] = at_rest_;
      results["rim_vertical_speed_m_per_s"] = s_.rim.vz;  // how far from rest the loading ended
      const double loaded_radius = s_.rim.z - s_.road.height_m;
      results["unloaded_radius_m"] = radius0_;
      results["loaded_radius_m"] = loaded_radius;
      results["vertical_deflection_m"] = radius0_ - loaded_radius;
      results["contact_area_m2"] = ground_area();
      results["rim_vertical_force_N"] = s_.rim.tyre_force_z_N;  // the tyre holding the rim up
      results[ground("vertical_force_N")] = ground_fz();
      if (road_under_terrain()) {  // the road's share and the terrain's lift
        results["road_vertical_force_N"] = s_.road.force_z_N;
        results["road_contact_area_m2"] = s_.road.contact_area_m2;
        results["terrain_vertical_force_N"] = s_.terrain.load_totals.force_N[2];
      }
      results["wheel_load_N"] = load_;
      // The rim's drop below where the undeformed tyre would touch the undisturbed
      // terrain surface z = 0: the sinkage less the tyre's deflection. The sinkage
      // (the rut below the undisturbed surface, thesis 5.3, 6.2) is the coupler's.
      if (port_ && !loaded_before_terrain()) results["rim_drop_m"] = free_radius(model, s_) - s_.rim.z;
      results["kinetic_energy_after_loading_J"] = s_.energy.kinetic_J;
      // On a terrain solver the footprint is the coupler's (contact_pressure.png);
      // a tyre loaded on its road before the terrain is placed has the road's.
      if (!port_ || loaded_before_terrain()) {
        // Thesis Figure 4.3: the footprint's pressure, its mean (load over the
        // road-facing area) and its peak (a node's force over its share).
        results["contact_pressure_max_Pa"] = write_footprint(record_->out_dir(), model, s_);
        results["contact_pressure_mean_Pa"] = s_.road.contact_area_m2 > 0 ? s_.road.force_z_N / s_.road.contact_area_m2
                                                                          : 0.0;
      }
      s_.damping_per_s = 0.0;
      break;
    }
    case kRolling: {
      if (st.rolling_s() <= 0) break;
      const auto& rim = t_.rim();
      const double turned = s_.rim.angle - a_w_;
      const long n = n_w_;
      results["rolling_distance_m"] = s_.rim.x;
      results["rolling_revolutions"] = s_.rim.angle / (2.0 * M_PI);
      results["rolling_radius_m"] = std::fabs(turned) > 1e-9 ? (s_.rim.x - x_w_) / turned : 0.0;
      results["rm2_Nm"] = n ? m_sum_ / n : 0.0;
      results[ground("longitudinal_force_N")] = n ? fx_sum_ / n : 0.0;
      results[ground("vertical_force_rolling_N")] = n ? fz_sum_ / n : 0.0;
      if (road_under_terrain()) {
        results["road_vertical_force_rolling_N"] = n ? road_fz_sum_ / n : 0.0;
        results["road_contact_area_rolling_m2"] = n ? road_area_sum_ / n : 0.0;
        results["terrain_vertical_force_rolling_N"] = n ? (fz_sum_ - road_fz_sum_) / n : 0.0;
        report_hydroplaning(results);
      }
      // The tyre's force on the rim along x (forward positive), which holds the
      // rim's prescribed forward speed: at a steady state the ground's longitudinal
      // force on the tyre (docs/force_decomposition.md, "Drawbar pull").
      results["rim_longitudinal_force_N"] = n ? rim_fx_sum_ / n : 0.0;
      // Window means: the rim height above the road is the lever arm of the road's
      // longitudinal force about the axle (moment balance of the tyre at steady state).
      results["loaded_radius_rolling_m"] = n ? h_sum_ / n : s_.rim.z - s_.road.height_m;
      results["spin_rate_rad_per_s"] = n ? w_sum_ / n : s_.rim.omega;
      results[ground("longitudinal_force_moment_Nm")] =
          n ? fx_sum_ / n * results["loaded_radius_rolling_m"].get<double>() : 0.0;
      results["energy_balance_error"] = s_.energy.balance_error();
      results["energy_balance_J"] = s_.energy.balance_J();
      results["drive_torque_Nm"] = rim.spin_case() == sc::RimSpec::kDriveTorqueNm ? rim.drive_torque_nm() : 0.0;
      results["averaging_window_s"] = average_window_;
      break;
    }
    case kDone:
      break;
  }
  stage_ = static_cast<Stage>(stage_ + 1);
  stage_begun_ = false;
}

TyreRun::WaterEnd TyreRun::water_end() const {
  // The reading ends where the tread reaches the downstream end of the water
  // (the scene's terrain blocks): beyond it the tyre lands on the bare road.
  constexpr double kNone = std::numeric_limits<double>::infinity();
  double water_end_x = kNone, surface_z = 0.0;
  if (scene_.sph().blocks_size() > 0) {
    double block_end = -kNone;
    surface_z = -kNone;
    for (const auto& b : scene_.sph().blocks())
      block_end = std::max(block_end, b.region().max().x()), surface_z = std::max(surface_z, b.region().max().z());
    water_end_x = std::min(scene_.sph().container().max().x(), block_end);
  }
  const double rim_height = record_->results().value("loaded_radius_m", radius0_) + s_.road.height_m - surface_z;
  return {water_end_x, tread_lead_at_surface_m(radius0_, rim_height)};
}

bool TyreRun::past_the_water() const {
  const WaterEnd end = water_end();
  return s_.rim.x + end.tread_lead_m >= end.x_m + std::fabs(s_.rim.vx) * kHydroplaningFilter_s;
}

void TyreRun::report_hydroplaning(nlohmann::json& results) {
  const WaterEnd end = water_end();
  const HydroplaningReading r = read_hydroplaning(hydroplaning_, load_, s_.rim.x, end.tread_lead_m, end.x_m, afloat_);
  if (r.samples_over_water < 2) return;
  auto* csv = &record_->series("road_share_vs_speed.csv",
                               {"time_s", "speed_m_per_s", "road_force_N", "water_lift_N", "road_share"});
  const RoadShareCurve& c = r.curve;
  double next = 0.0;
  for (std::size_t i = 0; i < c.time_s.size(); ++i) {
    if (c.time_s[i] < next && i + 1 < c.time_s.size()) continue;
    csv->row({c.time_s[i], c.speed_m_per_s[i], c.road_share[i] * load_, r.water_lift_N[i], c.road_share[i]});
    next = c.time_s[i] + csv_interval_;
  }
  results["hydroplaning"] = r.results;
  hydroplaning_curve_ = true;
}

void TyreRun::finalize(cosim::RunRecord& record) {
  if (!stepping_) return;  // mesh only, or the model was never built
  const Model3d& model = *model_;
  if (!failed()) frames_->write(model, s_);
  // A run stopped in its rolling stage (a signal, a failure) keeps the road force
  // against speed up to its last step: the hydroplaning reading of what it ran.
  if (stage_ == kRolling && stage_begun_ && road_under_terrain() && !hydroplaning_curve_) {
    report_hydroplaning(record.results());
    if (hydroplaning_curve_) record.results()["hydroplaning"]["stopped_in_the_rolling_stage"] = true;
  }
  nlohmann::json& summary = record.summary();
  summary["energy"] = energy_json(s_.energy);
  summary["dt_s"] = s_.dt_s;
  // Whole-run figures (inflation and set-up included); bench/tyre_bench times the step alone.
  const double wall = record.wall_s();
  const double per_element_step = s_.step ? wall / (double(s_.step) * model.mesh.hexes.size()) : 0.0;
  summary["performance"] = {{"steps_per_s", wall > 0 ? s_.step / wall : 0.0},
                            {"us_per_element_step", 1e6 * per_element_step},
                            {"core_us_per_element_step", 1e6 * per_element_step * cosim::max_threads()}};
  if (!joined()) return;
  const auto& st = s_.stage_times;
  const double coupled_steps = double(s_.step - coupled_from_step_);
  const double compute = st.internal_forces_s + st.contact_s + st.rest_s;
  auto& perf = summary["performance"];
  perf["coupled_steps"] = s_.step - coupled_from_step_;
  perf["coupling_windows"] = s_.terrain.exchange;
  perf["coupling_window_s"] = summary["coupling_window_s"];
  perf["tyre_substeps"] = s_.terrain.substeps;
  // What the terrain's loads gave the tyre over the run (the terrain books the same).
  const double* impulse = s_.terrain.impulse_Ns;
  record.results()["terrain_impulse_Ns"] = {impulse[0], impulse[1], impulse[2]};
  // How high the sent surface reached: the scene's band, or above it where the
  // terrain's particles (a splash) could reach higher.
  record.results()["highest_contact_band_m"] = s_.terrain.highest_band_m;
  perf["coupled_wall_s"] = wall - coupled_from_wall_;
  perf["exchange_wait_s"] = exchange_s_;
  perf["compute_s"] = compute;
  // Where the tyre's time goes (stage wall times summed over the coupled steps).
  perf["stages_s"] = {{"element_forces_and_gather", st.internal_forces_s},
                      {"road_contact", st.contact_s},
                      {"pressure_damping_rim_update_energy", st.rest_s}};
  perf["compute_s_per_step"] = coupled_steps > 0 ? compute / coupled_steps : 0.0;
}

}  // namespace

nlohmann::json run_tyre_scene(const cosim::LoadedScene& loaded, const RunOptions& options) {
  cosim::RunRecord record(loaded, options.out_dir, "tyre_fe", options.restart);
  if (options.restart_at) record.restart_at(*options.restart_at);
  TyreRun run(loaded, options);
  return cosim::run_participant(run, record, loaded.message.name(), options.quiet);
}

void validate_fe_body_scene(const cosim::LoadedScene& loaded, cosim::ValidationReport& report) {
  validate_tyre_scene(loaded, report);
  validate_tread_block_scene(loaded, report);
}

nlohmann::json run_fe_body_scene(const cosim::LoadedScene& loaded, const RunOptions& options) {
  return loaded.message.has_tread_block() ? run_tread_block_scene(loaded, options) : run_tyre_scene(loaded, options);
}

}  // namespace tyre_fe
