// The tyre's run (tyre_run.hpp): the participant's hooks, the model built in
// initialize(), the terrain it joins, its outputs and checkpoints. The stage
// machine is the procedure's (tyre_procedure.cpp), the sums and results are
// tyre_results.cpp's.
#include "tyre_fe/run.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/parallel.hpp"
#include "tyre_fe/energy_split.hpp"
#include "tyre_fe/scene.hpp"
#include "tyre_fe/state_checkpoint.hpp"
#include "tyre_fe/tread_block.hpp"
#include "tyre_run.hpp"

namespace tyre_fe {

namespace {

// The mesh's counts into the summary and results.
void mesh_summary(const CrossSection& section, const Mesh3D& mesh, cosim::RunRecord& record) {
  nlohmann::json& summary = record.summary();
  nlohmann::json& results = record.results();
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
}

// The stable step and the mass scaling behind it into the summary.
void time_step_summary(const Model3d& model, const Model3dOptions& options, nlohmann::json& summary) {
  summary["time_step"] = {{"stable_dt_s", model.stable_dt_s},
                          {"unscaled_stable_dt_s", model.unscaled_dt_s},
                          {"controlling_region", region_name(model.mesh.hex_region[model.dt_controlling_element])},
                          {"mass_scaling_target_dt_s", options.mass_scaling_target_dt_s},
                          {"physical_mass_kg", model.physical_mass_kg},
                          {"added_mass_kg", model.added_mass_kg},
                          {"added_mass_percent", 100.0 * model.added_mass_kg / model.physical_mass_kg}};
  for (int r = 0; r < kRegionCount; ++r)
    if (model.region_min_dt_s[r] > 0.0)
      summary["time_step"]["regions"][region_name(static_cast<Region>(r))] = {
          {"min_stable_dt_s", model.region_min_dt_s[r]}, {"added_mass_kg", model.region_added_mass_kg[r]}};
}

}  // namespace

double TyreRun::initialize(cosim::RunRecord& record) {
  record_ = &record;
  nlohmann::json& summary = record.summary();
  const std::string out = record.out_dir();
  const TyreSetup setup = tyre_setup(loaded_);
  summary["tyre_size"] = setup.size_designation;
  summary["materials_source"] = setup.materials_source;
  summary["bulk_to_shear_ratio"] = setup.bulk_to_shear_ratio;
  const CrossSection section = make_section(setup);
  Mesh3D mesh = revolve(section, setup.pattern);
  mesh_summary(section, mesh, record);
  const bool mesh_only = options_.mesh_only || t_.mesh_only();
  if (options_.write_vtk || mesh_only) {
    write_cross_section_vtk(out + "/cross_section.vtk", section, section.nodes);
    write_mesh_vtk(out + "/mesh3d.vtk", mesh, mesh.nodes);
    write_facets_vtk(out + "/surface.vtk", mesh, mesh.nodes);
  }
  // The model (masses, stable step) is cheap to build: mesh-only runs report the step too.
  Model3dOptions mo;
  mo.time_step_safety = time_step_safety(scene_);
  mo.mass_scaling_target_dt_s = t_.mass_scaling_target_dt_s();
  model_ = std::make_unique<Model3d>(build_model3d(std::move(mesh), setup.materials, section, mo));
  time_step_summary(*model_, mo, summary);
  if (mesh_only) {
    stage_ = kDone;
    return 0.0;
  }
  inflate_and_transfer(section, setup);
  open_series(record);
  max_steps_ = scene_.time().max_steps();
  frames_ = std::make_unique<FrameWriter>(out, options_.write_vtk ? scene_.output().vtk_interval_s() : 0.0);
  stepping_ = true;
  return cosim::planned_end_time_s(scene_);  // transfer check, loading, rolling
}

void TyreRun::inflate_and_transfer(const CrossSection& section, const TyreSetup& setup) {
  const Model3d& model = *model_;
  nlohmann::json& results = record_->results();
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
  centre_r0_m_ = section.nodes[centre_][0];
  results["axisym_radial_growth_m"] = axi.nodes[centre_][0] - centre_r0_m_;
  results["axisym_steps"] = axi.steps;
  results["axisym_residual_ratio"] = axi.residual_ratio;
  write_cross_section_vtk(record_->path("cross_section_inflated.vtk"), section, axi.nodes);

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
}

void TyreRun::open_series(cosim::RunRecord& record) {
  const GroundNames g = ground();
  tyre_columns_ = {"time_s",
                   "stage",
                   "rim_x_m",
                   "rim_z_m",
                   "rim_angle_rad",
                   "rim_vx_m_per_s",
                   "rim_vz_m_per_s",
                   "rim_omega_rad_per_s",
                   "rim_vertical_force_N",
                   "rm2_Nm",
                   g("force_x_N"),
                   g("force_y_N"),
                   g("force_z_N"),
                   "rim_longitudinal_force_N",
                   "contact_area_m2",
                   "kinetic_J",
                   "internal_J",
                   "hourglass_J",
                   "external_work_J",
                   "energy_balance_error",
                   "crown_radial_growth_m"};
  for (const cosim::EnergyValue& v : energy_split(Energies{})) tyre_columns_.push_back(v.key);  // the split's
  csv_ = &record.series("tyre.csv", tyre_columns_);
  // A road under the terrain: the road's force and area apart, and the terrain's lift.
  if (road_under_terrain())
    road_csv_ = &record.series("road.csv", {"time_s", "road_force_x_N", "road_force_z_N", "road_contact_area_m2",
                                            "terrain_force_x_N", "terrain_force_z_N", "rim_vx_m_per_s"});
  csv_interval_s_ = scene_.output().csv_interval_s();
}

// The run's own clocks, stage and sums, one named field each.
void TyreRun::save(cosim::CheckpointWriter& out) const {
  save_state(s_, out);
  frames_->save(out);
  for (const auto& [name, value] : run_fields(*this)) out.put_value<double>("run." + name, *value);
  for (const auto& [name, flag] : run_flags(*this)) out.put_value<std::uint8_t>("run." + name, *flag ? 1 : 0);
  out.put_value<std::uint64_t>("run.stage", std::uint64_t(stage_));
  out.put_value<std::uint64_t>("run.window.steps", std::uint64_t(window_.steps));
  hydroplaning_.save(out);
  if (joined()) save_terrain_coupling(s_.terrain, coupling_window_s(), out);
}

void TyreRun::restore(const cosim::CheckpointReader& in) {
  const double own_dt = s_.dt_s;  // the step the tyre proposes when it joins a terrain
  restore_state(in, s_);
  frames_->restore(in);
  for (const auto& [name, value] : run_fields(*this)) *value = in.get_value<double>("run." + name);
  for (const auto& [name, flag] : run_flags(*this)) *flag = in.get_value<std::uint8_t>("run." + name) != 0;
  const auto stage = in.get_value<std::uint64_t>("run.stage");
  if (stage > kDone) throw cosim::Error(in.path() + ": run.stage " + std::to_string(stage) + " unknown");
  stage_ = static_cast<Stage>(stage);
  window_.steps = static_cast<long>(in.get_value<std::uint64_t>("run.window.steps"));
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
  coupled_from_wall_s_ = record_->wall_s();
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
  coupled_from_wall_s_ = record_->wall_s();
  nlohmann::json& summary = record_->summary();
  summary["coupled_dt_s"] = s_.dt_s;
  summary["coupling_window_s"] = window;
  summary["tyre_substeps"] = s_.terrain.substeps;
  record_->results()["coupled_time_step_s"] = s_.dt_s;
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
  if (s_.time_s >= next_csv_s_ || stage_done_) {
    std::vector<double> row{s_.time_s,
                            double(stage_),
                            s_.rim.x,
                            s_.rim.z,
                            s_.rim.angle,
                            s_.rim.vx,
                            s_.rim.vz,
                            s_.rim.omega,
                            s_.rim.tyre_force_z_N,
                            s_.rim.rm2_Nm,
                            ground_fx(s_),
                            ground_fy(s_),
                            ground_fz(s_),
                            s_.rim.tyre_force_x_N,
                            ground_area(s_),
                            s_.energy.kinetic_J,
                            s_.energy.internal_J,
                            s_.energy.hourglass_J,
                            s_.energy.external_work_J,
                            s_.energy.balance_error(),
                            mean_radius_of(model_->mesh, s_, centre_) - centre_r0_m_};
    for (const cosim::EnergyValue& v : energy_split(s_.energy)) row.push_back(v.value);
    csv_->row(row);
    if (road_csv_)
      road_csv_->row({s_.time_s, s_.road.force_x_N, s_.road.force_z_N, s_.road.contact_area_m2,
                      s_.terrain.load_totals.force_N[0], s_.terrain.load_totals.force_N[2], s_.rim.vx});
    next_csv_s_ = s_.time_s + csv_interval_s_;
  }
  frames_->maybe_write(*model_, s_);
}

// Where the work done on the tyre went over time: the split's terms stacked,
// the work done on the tyre as a line over them.
void TyreRun::plot_energy_split(cosim::RunRecord& record) {
  auto column = [&](const char* key) {
    return static_cast<int>(std::find(tyre_columns_.begin(), tyre_columns_.end(), key) - tyre_columns_.begin()) + 1;
  };
  const cosim::EnergySplit& split = tyre_energy_split();
  std::vector<cosim::PlotSeries> stacked;
  for (const cosim::EnergyTerm& t : split.went_to) stacked.push_back({column(t.key), t.label});
  record.plot_stacked("tyre.csv", "energy_split.png", 1, stacked, {{column(split.total.key), "work done on the tyre"}},
                      scene_.name() + ": where the work done on the tyre went", "time [s]", "energy [J]");
}

void TyreRun::plots(cosim::RunRecord& record) {
  if (stepping_) write_plots(record.out_dir()), plot_energy_split(record);
  if (!hydroplaning_curve_) return;
  const double tenth = kHydroplaningRoadShare * loading_.load_N;
  record.plot("road_share_vs_speed.csv", "road_force_vs_speed.png", 2,
              {{3, "road force on the tyre"}, {4, "water lift on the tyre"}},
              scene_.name() + ": road force against speed (" + cosim::number_text(1e3 * kHydroplaningFilter_s) +
                  " ms mean)",
              "forward speed [m/s]", "vertical force [N]",
              "set arrow from graph 0, first " + cosim::number_text(tenth) + " to graph 1, first " +
                  cosim::number_text(tenth) + " nohead dt 2 lc rgb 'gray40'\n");
}

void TyreRun::finalize(cosim::RunRecord& record) {
  if (!stepping_) return;  // mesh only, or the model was never built
  const Model3d& model = *model_;
  if (!failed()) frames_->write(model, s_);
  // A run stopped in its rolling stage (a signal, a failure) keeps the road force
  // against speed up to its last step: the hydroplaning reading of what it ran.
  if (stage_ == kRolling && stage_begun_ && road_under_terrain() && !hydroplaning_curve_) {
    report_hydroplaning_now();
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
  if (joined()) coupled_performance(summary, wall);
}

void TyreRun::coupled_performance(nlohmann::json& summary, double wall) {
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
  record_->results()["terrain_impulse_Ns"] = {impulse[0], impulse[1], impulse[2]};
  // How high the sent surface reached: the scene's band, or above it where the
  // terrain's particles (a splash) could reach higher.
  record_->results()["highest_contact_band_m"] = s_.terrain.highest_band_m;
  perf["coupled_wall_s"] = wall - coupled_from_wall_s_;
  perf["exchange_wait_s"] = exchange_s_;
  perf["compute_s"] = compute;
  // Where the tyre's time goes (stage wall times summed over the coupled steps).
  perf["stages_s"] = {{"element_forces_and_gather", st.internal_forces_s},
                      {"road_contact", st.contact_s},
                      {"pressure_damping_rim_update_energy", st.rest_s}};
  perf["compute_s_per_step"] = coupled_steps > 0 ? compute / coupled_steps : 0.0;
}

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
