// A tread block pushed into the terrain (thesis 3.4) under the run skeleton
// (cosim/participant.hpp): the block's mesh and model in initialize(), then
// steps of the tyre's explicit stages (solver3d.hpp) with the same exchange as
// the tyre's (run.cpp), a coupled participant's (cosim_coupling/coupled_participant.hpp):
// at a coupling window's start
//   send surface -> compute_forces -> receive loads -> add_terrain_loads -> integrate,
// the reference node (the "rim") moving the top face down along the push path,
// or (sliding, thesis 4.3) carrying a load with z free and sliding along x.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cosim/error.hpp"
#include "cosim/participant.hpp"
#include "cosim/ramp.hpp"
#include "tyre_fe/model3d.hpp"
#include "tyre_fe/outputs.hpp"
#include "tyre_fe/run.hpp"
#include "tyre_fe/scene.hpp"
#include "tyre_fe/solver3d.hpp"
#include "tyre_fe/tread_block.hpp"

namespace tyre_fe {
namespace {

// The block does not checkpoint, so it never declares itself joined
// (joined_with_window: a participant that checkpoints between windows): a stop
// signal ends its run at once.
class TreadBlockRun final : public cosim::coupling::CoupledParticipant {
 public:
  TreadBlockRun(const cosim::LoadedScene& loaded, const RunOptions& options)
      : CoupledParticipant(options.terrain), port_(options.terrain), loaded_(loaded), options_(options) {}

  double initialize(cosim::RunRecord& record) override;
  double time_s() const override { return s_.time_s; }
  std::uint64_t steps() const override { return s_.step; }
  void output(cosim::RunRecord& record) override;
  void finalize(cosim::RunRecord& record) override;
  void plots(cosim::RunRecord& record) override {
    if (slide_csv_) {
      record.plot("block_slide.csv", "block_slide_forces.png", 1,
                  {{5, "longitudinal force (holder)"}, {6, "road force x"}, {9, "water force x"}},
                  loaded_.message.name() + ": longitudinal forces on the sliding block", "time [s]", "force [N]");
      record.plot("block_slide.csv", "block_slide_load_share.png", 1, {{7, "road force z"}, {10, "water force z"}},
                  loaded_.message.name() + ": who carries the load", "time [s]", "force [N]");
    }
    if (!csv_) return;
    record.plot("tread_block.csv", "tread_block_force.png", 3, {{6, "terrain on the block, vertical"}},
                loaded_.message.name() + ": force against the depth of the ribs", "depth of the rib faces below the snow [m]",
                "force [N]");
  }

 private:
  // Until the push and hold (or the slide) are over; false then.
  bool before_exchange() override { return s_.time_s < end_s_ - 0.5 * s_.dt_s; }
  // At a coupling window's start.
  bool exchange_due() const override { return s_.terrain.substep == 0; }
  // Surface out, element forces, loads in.
  bool exchange() override;
  // The rest of the step, then the per-step sums.
  bool after_exchange(bool peers_go_on) override;
  // Lowest point of the ribs' faces below the terrain surface z = 0 [m] (the reference node's path).
  double face_depth_m() const { return displacement_m() - setup_.initial_gap_m; }
  double displacement_m() const { return -s_.rim.z; }
  // The push: the reference node's drive along its path.
  RimDrive push_drive() const;
  // The slide (thesis 4.3): the reference node's drive now, its per-step sums and its results.
  RimDrive slide_drive() const;
  void slide_sums();
  void slide_results(nlohmann::json& results) const;

  TerrainPort* port_;
  const cosim::LoadedScene& loaded_;
  RunOptions options_;
  TreadBlockSetup setup_;
  std::unique_ptr<Model3d> model_;
  State3d s_;
  std::unique_ptr<FrameWriter> frames_;
  cosim::CsvWriter* csv_ = nullptr;
  double end_s_ = 0.0, next_csv_ = 0.0, csv_interval_ = 0.0, exchange_s_ = 0.0;
  double max_force_z_N_ = 0.0;
  cosim::CsvWriter* slide_csv_ = nullptr;
  // Sums over the slide's averaging window: the holder's longitudinal force, the
  // road's and the water's forces, the road's contact area.
  double sum_fx_ = 0, sum_road_fx_ = 0, sum_road_fz_ = 0, sum_area_ = 0, sum_water_fx_ = 0, sum_water_fz_ = 0;
  double sum_fx2_ = 0, window_x0_ = 0.0;
  long n_window_ = 0;
  bool forces_computed_ = false;  // by this step's exchange
};

double TreadBlockRun::initialize(cosim::RunRecord& record) {
  if (!port_) throw cosim::Error("a tread block runs on a terrain solver only: start it with `cosim run`");
  setup_ = tread_block_setup(loaded_);
  const auto& scene = loaded_.message;
  // The ribs' faces start initial_gap_m above the terrain surface z = 0.
  Mesh3D mesh = make_tread_block_mesh(setup_.geometry, setup_.initial_gap_m);
  nlohmann::json& summary = record.summary();
  nlohmann::json& results = record.results();
  results["nodes"] = mesh.nodes.size();
  results["elements"] = mesh.hexes.size();
  results["facets"] = mesh.facets.size();
  summary["elements"] = mesh.hexes.size();
  if (options_.write_vtk) write_facets_vtk(record.path("surface.vtk"), mesh, mesh.nodes);
  Model3dOptions mo;
  mo.time_step_safety = time_step_safety(scene);
  model_ = std::make_unique<Model3d>(build_model3d(std::move(mesh), setup_.materials, CrossSection{}, mo));
  const Model3d& model = *model_;
  summary["time_step"] = {{"stable_dt_s", model.stable_dt_s}, {"mass_kg", model.physical_mass_kg}};
  s_ = make_state3d(model, model.mesh.nodes, setup_.reference_node_mass_kg, 0.0);
  s_.rim.inertia_kg_m2 = 1.0;  // the spin is held at 0: any positive inertia
  s_.road.height_m = 0.0;      // heights are measured from the terrain surface
  s_.terrain.surface = make_contact_surface(model, s_);
  s_.terrain.band_m = scene.coupling().contact_band_m();
  if (scene.coupling().rigid_road_under_terrain()) {
    // The road at the terrain's floor (a water film on it), as under a tyre (run.cpp).
    const auto& road = scene.tread_block().road();
    set_road(s_, scene.sph().container().min().z(), road.friction_coefficient(), road.penalty_scale());
  }
  if (setup_.sliding())
    slide_csv_ = &record.series("block_slide.csv",
                                {"time_s", "reference_x_m", "reference_z_m", "slide_speed_m_per_s",
                                 "longitudinal_force_N", "road_force_x_N", "road_force_z_N", "road_contact_area_m2",
                                 "water_force_x_N", "water_force_z_N"});
  csv_ = &record.series("tread_block.csv", {"time_s", "reference_displacement_m", "face_depth_m",
                                            "terrain_force_x_N", "terrain_force_y_N", "terrain_force_z_N",
                                            "contact_area_m2", "holder_force_z_N", "kinetic_J", "internal_J",
                                            "energy_balance_error"});
  csv_interval_ = scene.output().csv_interval_s();
  frames_ = std::make_unique<FrameWriter>(record.out_dir(), options_.write_vtk ? scene.output().vtk_interval_s() : 0.0,
                                          "tread_block");
  if (!options_.quiet)
    std::fprintf(stderr, "[%s] tread block: %zu hexahedra, joining the terrain and the coupler (%zu surface facets)\n",
                 scene.name().c_str(), model.mesh.hexes.size(), s_.terrain.surface.facet_count());
  const double window = connect_to_terrain(*port_, s_);
  summary["coupled_dt_s"] = s_.dt_s;
  summary["coupling_window_s"] = window;
  summary["tyre_substeps"] = s_.terrain.substeps;
  end_s_ = cosim::planned_end_time_s(scene);  // the push and the hold; the coupler plans the same
  return end_s_;
}

bool TreadBlockRun::exchange() {
  exchange_with_terrain(*model_, s_, *port_, exchange_s_);
  forces_computed_ = true;
  return true;  // a terrain that is gone throws
}

bool TreadBlockRun::after_exchange(bool) {
  complete_step_on_terrain(*model_, s_, setup_.sliding() ? slide_drive() : push_drive(), forces_computed_);
  forces_computed_ = false;
  if (setup_.sliding()) slide_sums();
  max_force_z_N_ = std::max(max_force_z_N_, s_.terrain.load_totals.force_N[2]);
  return true;
}

// The reference node moves from d(t) to d(t + dt) in this step: the path is met exactly at every step.
RimDrive TreadBlockRun::push_drive() const {
  RimDrive drive;
  drive.prescribe_vz = true;
  drive.vertical_speed_m_per_s =
      -(push_displacement_m(setup_.path, s_.time_s + s_.dt_s) - push_displacement_m(setup_.path, s_.time_s)) / s_.dt_s;
  return drive;
}

RimDrive TreadBlockRun::slide_drive() const {
  const SlideSpec& sl = setup_.slide;
  RimDrive d;  // spin held at 0, z free
  d.wheel_load_N = sl.load_N * cosim::ramp(cosim::RampCurve::smoothstep, s_.time_s, sl.load_ramp_s);
  d.hold_x = false;  // x moves at the prescribed speed (0 until the slide starts)
  const double sliding_s = s_.time_s - sl.start_s();
  d.forward_speed_m_per_s =
      sliding_s > 0.0 ? cosim::ramp(cosim::RampCurve::smoothstep, sliding_s, sl.speed_ramp_s, sl.speed_m_per_s) : 0.0;
  return d;
}

void TreadBlockRun::slide_sums() {
  if (s_.time_s < setup_.slide.end_s() - setup_.slide.average_s) return;
  if (n_window_ == 0) window_x0_ = s_.rim.x;
  // The holder pulls the block forward: the tyre_fe rim's force from the block, reversed.
  const double fx = -s_.rim.tyre_force_x_N;
  sum_fx_ += fx, sum_fx2_ += fx * fx;
  sum_road_fx_ += s_.road.force_x_N, sum_road_fz_ += s_.road.force_z_N, sum_area_ += s_.road.contact_area_m2;
  sum_water_fx_ += s_.terrain.load_totals.force_N[0], sum_water_fz_ += s_.terrain.load_totals.force_N[2];
  ++n_window_;
}

void TreadBlockRun::slide_results(nlohmann::json& results) const {
  const SlideSpec& sl = setup_.slide;
  const double n = n_window_ > 0 ? double(n_window_) : 1.0;
  const double fx = sum_fx_ / n;
  results["load_N"] = sl.load_N;
  results["slide_speed_m_per_s"] = sl.speed_m_per_s;
  results["averaging_window_s"] = sl.average_s;
  results["slide_distance_in_window_m"] = s_.rim.x - window_x0_;
  results["longitudinal_force_N"] = fx;  // the holder's pull, the thesis's F (Table 4.3)
  results["longitudinal_force_std_N"] = std::sqrt(std::max(0.0, sum_fx2_ / n - fx * fx));
  results["friction_coefficient"] = fx / sl.load_N;  // mu = F / P
  results["road_force_x_N"] = sum_road_fx_ / n;
  results["road_vertical_force_N"] = sum_road_fz_ / n;
  results["road_contact_area_m2"] = sum_area_ / n;
  results["water_force_x_N"] = sum_water_fx_ / n;
  results["water_vertical_force_N"] = sum_water_fz_ / n;  // the film's lift
  results["road_load_share"] = sum_road_fz_ / n / sl.load_N;
}

void TreadBlockRun::output(cosim::RunRecord&) {
  if (slide_csv_ && s_.time_s >= next_csv_) {
    const auto& w = s_.terrain.load_totals.force_N;
    slide_csv_->row({s_.time_s, s_.rim.x, s_.rim.z, s_.rim.vx, -s_.rim.tyre_force_x_N, s_.road.force_x_N,
                     s_.road.force_z_N, s_.road.contact_area_m2, w[0], w[2]});
  }
  if (s_.time_s >= next_csv_) {
    const auto& f = s_.terrain.load_totals.force_N;
    csv_->row({s_.time_s, displacement_m(), face_depth_m(), f[0], f[1], f[2], s_.terrain.load_totals.contact_area_m2,
               -s_.rim.tyre_force_z_N, s_.energy.kinetic_J, s_.energy.internal_J, s_.energy.balance_error()});
    next_csv_ = s_.time_s + csv_interval_;
  }
  frames_->maybe_write(*model_, s_);
}

void TreadBlockRun::finalize(cosim::RunRecord& record) {
  if (!model_) return;
  if (!failed()) frames_->write(*model_, s_);
  nlohmann::json& results = record.results();
  const auto& f = s_.terrain.load_totals.force_N;
  results["face_depth_m"] = face_depth_m();
  results["terrain_force_z_N"] = f[2];
  results["largest_terrain_force_z_N"] = max_force_z_N_;
  results["terrain_force_x_N"] = f[0];
  results["contact_area_m2"] = s_.terrain.load_totals.contact_area_m2;
  const double* impulse = s_.terrain.impulse_Ns;
  results["terrain_impulse_Ns"] = {impulse[0], impulse[1], impulse[2]};
  results["energy_balance_error"] = s_.energy.balance_error();
  if (setup_.sliding()) {
    slide_results(results);
    if (s_.road.present) write_footprint(record.out_dir(), *model_, s_);  // the road's contact pressure at the end
  }
  record.summary()["dt_s"] = s_.dt_s;
  record.summary()["performance"] = {{"steps_per_s", record.wall_s() > 0 ? s_.step / record.wall_s() : 0.0},
                                     {"exchange_wait_s", exchange_s_}};
}

}  // namespace

nlohmann::json run_tread_block_scene(const cosim::LoadedScene& loaded, const RunOptions& options) {
  cosim::RunRecord record(loaded, options.out_dir, "tyre_fe");
  TreadBlockRun run(loaded, options);
  return cosim::run_participant(run, record, loaded.message.name(), options.quiet);
}

}  // namespace tyre_fe
