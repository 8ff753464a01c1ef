// The SPH terrain's run (sph_run.hpp): its set-up, its step as the coupled
// participant's stages, its checkpoint and the bodies' rest criterion.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/scene_io.hpp"
#include "snow_sph/scene.hpp"
#include "sph_run.hpp"

namespace snow_sph {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

double SphRun::initialize(cosim::RunRecord& record) {
  model_ = std::make_unique<Model>(build_model(scene_));
  Model& model = *model_;
  solver_ = std::make_unique<Solver>(model);
  if (surface_port_) {
    // Planned end: the surface owner's stages (the owner ends the run), as the
    // tyre and the coupler plan it. In a coupled run it sets only the progress
    // line and the floor-pressure probe's window, which no coupled scene uses.
    model.settings.end_time = cosim::planned_end_time_s(scene_);
    model.settings.max_steps = 0;
  }
  describe_setup(record);
  probe_from_ = model.settings.end_time - scene_.sph().probes().average_last_s();
  csv_interval_ = scene_.output().csv_interval_s();
  vtk_interval_ = options_.write_vtk ? scene_.output().vtk_interval_s() : 0.0;
  floor_x_ = 0.5 * (model.container_min[0] + model.container_max[0]);
  floor_y_ = 0.5 * (model.container_min[1] + model.container_max[1]);
  if (surface_port_) join_coupled_run(record);
  solver_->initialise();
  open_series(record);
  record_rows(true);
  if (vtk_) write_frame(), next_vtk_ = solver_->time() + vtk_interval_;
  return model.settings.end_time;
}

void SphRun::join_coupled_run(cosim::RunRecord& record) {
  Model& model = *model_;
  const Particles& p = model.particles;
  rut_grid_ = make_rut_grid(p.n_real, p.x.data(), p.y.data(), p.z.data(), model.settings.spacing);
  const auto& c = scene_.coupling();
  SurfaceContactParameters contact;
  contact.particle_radius_m = model.particle_radius_m();
  particle_radius_m_ = contact.particle_radius_m;
  contact.stiffness_N_per_m = model.settings.contact_stiffness * c.contact_stiffness_scale();
  solver_->couple(contact);
  solver_->place_around_surface_owner(c.place_terrain_around_loaded_tyre());
  // A particle still moving faster than 1 cm/s stays in the active domain
  // (docs/coupling.md): the resting terrain is at rest to well below that.
  solver_->set_active_domain(c.active_domain_margin_m(), 0.01, c.active_domain_wake_limit_m());
  solver_->prepare();  // sound speeds and accelerations of the first step
  const double limit = solver_->stability_limit_dt();
  // A restart joins at its checkpoint's exchange count (the next exchange to make).
  const double agreed = surface_port_->connect(model.settings.cfl * limit, record.resume_step());
  if (!(agreed > 0) || agreed > limit)
    throw cosim::Error("the agreed coupled time step " + cosim::number_text(agreed) +
                       " s is above the terrain's stable limit " + cosim::number_text(limit) + " s");
  model.settings.coupling_window_s = agreed;
  joined_with_window(agreed);
  wall_at_coupling_s_ = record.wall_s();
  nlohmann::json& summary = record.summary();
  summary["coupled_dt_s"] = agreed;
  summary["surface_contact"] = {{"particle_radius_m", contact.particle_radius_m},
                                {"stiffness_N_per_m", contact.stiffness_N_per_m},
                                {"damping_ratio", contact.damping_ratio}};
  contact_csv_ = &record.series("terrain_contact.csv",
                                {"time_s", "force_on_surface_x_N", "force_on_surface_y_N", "force_on_surface_z_N",
                                 "contact_area_m2", "particles_in_contact", "drained_water_particles",
                                 "max_penetration_m", "deepest_particle_x_m", "deepest_particle_z_m", "deepest_facet",
                                 "particles_behind_surface", "particle_reach_z_m"});
  // Exchange 0 with the particles at t_0; a restart's state and held loads
  // come from its checkpoint instead.
  if (record.resume_step() == 0) stopped_ = !exchange_surface(0);
}

bool SphRun::exchange_surface(std::uint64_t exchange) {
  const auto t0 = std::chrono::steady_clock::now();
  const cosim::SurfaceState* state = surface_port_->surface(exchange);
  exchange_wait_s_ += seconds_since(t0);
  if (state) assemble_contact_surface(surface_port_->topology(), *state, surface_, compact_scratch_);
  // The terrain's clock starts at the owner's: a tyre joins after its inflation
  // check, or after its loading on the road (place_terrain_around_loaded_tyre).
  if (state && exchange == 0) solver_->start_clock_at(state->time_s);
  solver_->contact_surface(state ? &surface_ : nullptr, exchange);
  if (!state) return false;
  const SurfaceContactResult& l = solver_->surface_loads();
  if (l.max_penetration_m > max_penetration_m_) {
    max_penetration_m_ = l.max_penetration_m;
    deepest_ = {solver_->time(), l.deepest_x_m, l.deepest_y_m, l.deepest_z_m, double(l.deepest_facet)};
  }
  sparse_surface_loads(*state, l, loads_out_);
  const auto t1 = std::chrono::steady_clock::now();
  surface_port_->send_loads(loads_out_);
  exchange_wait_s_ += seconds_since(t1);
  exchange_ = exchange;
  return true;
}

bool SphRun::before_exchange() {
  const Settings& settings = model_->settings;
  if (stopped_) return false;
  if (!surface_port_ && !(solver_->time() < settings.end_time - 1e-12 &&
                          (settings.max_steps == 0 || solver_->steps() < settings.max_steps)))
    return false;
  if (!surface_port_ && bodies_at_rest()) return false;
  step_stats_ = solver_->advance_to_exchange();
  ++windows_;
  report_substeps(step_stats_);
  return true;
}

bool SphRun::after_exchange(bool peers_go_on) {
  solver_->finish_window();
  if (!peers_go_on) {  // the surface's owner ended the run during this step
    stopped_ = true;
    return false;
  }
  const StepStats& st = step_stats_;
  track_rest();
  dt_min_ = std::min(dt_min_, st.dt), dt_max_ = std::max(dt_max_, st.dt), dt_sum_ += st.dt;
  clamped_ += st.clamped;
  last_dt_ = st.dt;
  if (!solver_->finite())
    throw cosim::Error("the solution became non-finite (NaN/Inf) at step " + std::to_string(solver_->steps()) +
                       ", t = " + cosim::number_text(solver_->time()) + " s");
  return true;
}

// The first sub-stepped window and every new most in one window, with what
// sets the limit after it (a sub-stepping run's cost is this cause's).
void SphRun::report_substeps(const StepStats& st) {
  if (st.substeps <= reported_substeps_) return;
  reported_substeps_ = st.substeps;
  substeps_cause_ = solver_->limit_cause();
  std::fprintf(stderr,
               "[%s] t = %s s: the terrain's stable limit (smallest %s s) is below the coupling window %s s; "
               "%u sub-steps in this window, the most so far (now set by %s; docs/coupling.md)\n",
               scene_.name().c_str(), cosim::number_text(solver_->time()).c_str(),
               cosim::number_text(solver_->smallest_limit_dt()).c_str(), cosim::number_text(st.dt).c_str(),
               st.substeps, substeps_cause_.c_str());
}

// One named record per quantity (cosim/checkpoint.hpp).
void SphRun::save(cosim::CheckpointWriter& out) const {
  solver_->save(out);
  out.put_value("run.dt_min_s", dt_min_);
  out.put_value("run.dt_max_s", dt_max_);
  out.put_value("run.dt_sum_s", dt_sum_);
  out.put_value("run.floor_pressure_time_integral_Pa_s", probe_sum_);
  out.put_value("run.floor_pressure_averaged_s", probe_time_);
  out.put_value("run.last_dt_s", last_dt_);
  out.put_value("run.next_csv_row_s", next_csv_);
  out.put_value("run.next_vtk_frame_s", next_vtk_);
  out.put_value("run.max_penetration_m", max_penetration_m_);
  out.put_value("run.deepest_contact_time_s", deepest_.time_s);
  out.put_value("run.deepest_contact_particle_x_m", deepest_.particle_x_m);
  out.put_value("run.deepest_contact_particle_y_m", deepest_.particle_y_m);
  out.put_value("run.deepest_contact_particle_z_m", deepest_.particle_z_m);
  out.put_value("run.deepest_contact_facet", deepest_.facet);
  out.put_value<std::uint64_t>("run.last_exchange", exchange_);
  out.put_value<std::uint64_t>("run.steps_made", windows_);
  out.put_value<std::uint64_t>("run.wall_clamps", clamped_);
  out.put_value<std::uint64_t>("run.stopped", stopped_ ? 1u : 0u);
  out.put("run.vtk_frame_times", vtk_ ? vtk_->frame_times() : std::vector<double>{});
}

void SphRun::restore(const cosim::CheckpointReader& in) {
  solver_->restore(in);
  dt_min_ = in.get_value<double>("run.dt_min_s");
  dt_max_ = in.get_value<double>("run.dt_max_s");
  dt_sum_ = in.get_value<double>("run.dt_sum_s");
  probe_sum_ = in.get_value<double>("run.floor_pressure_time_integral_Pa_s");
  probe_time_ = in.get_value<double>("run.floor_pressure_averaged_s");
  last_dt_ = in.get_value<double>("run.last_dt_s");
  next_csv_ = in.get_value<double>("run.next_csv_row_s");
  next_vtk_ = in.get_value<double>("run.next_vtk_frame_s");
  max_penetration_m_ = in.get_value<double>("run.max_penetration_m");
  deepest_.time_s = in.get_value<double>("run.deepest_contact_time_s");
  deepest_.particle_x_m = in.get_value<double>("run.deepest_contact_particle_x_m");
  deepest_.particle_y_m = in.get_value<double>("run.deepest_contact_particle_y_m");
  deepest_.particle_z_m = in.get_value<double>("run.deepest_contact_particle_z_m");
  deepest_.facet = in.get_value<double>("run.deepest_contact_facet");
  exchange_ = in.get_value<std::uint64_t>("run.last_exchange");
  windows_ = in.get_value<std::uint64_t>("run.steps_made");
  clamped_ = in.get_value<std::uint64_t>("run.wall_clamps");
  stopped_ = in.get_value<std::uint64_t>("run.stopped") != 0;
  const auto frames = in.get<double>("run.vtk_frame_times");
  if (vtk_) vtk_->resume(frames);
}

void SphRun::track_rest() {
  const double t = solver_->time();
  for (RigidBody& b : model_->bodies) {
    if (!(b.rest_speed > 0.0)) continue;
    const bool slow = t >= b.ramp_time && std::abs(b.vz) < b.rest_speed;
    if (!slow) b.slow_since_s = -1.0;
    else if (b.slow_since_s < 0.0) b.slow_since_s = t;
  }
}

// Every body with a rest criterion has been slow for its hold time (and there is at least one).
bool SphRun::bodies_at_rest() const {
  bool any = false;
  for (const RigidBody& b : model_->bodies) {
    if (!(b.rest_speed > 0.0)) continue;
    if (!b.at_rest(solver_->time())) return false;
    any = true;
  }
  return any;
}

nlohmann::json run_scene(const cosim::LoadedScene& loaded, const RunOptions& options) {
  cosim::RunRecord record(loaded, options.out_dir, "snow_sph", options.restart);
  if (options.restart_at) record.restart_at(*options.restart_at);
  SphRun run(loaded, options);
  return cosim::run_participant(run, record, loaded.message.name(), options.quiet);
}

}  // namespace snow_sph
