#include "snow_sph/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <cstdio>
#include <memory>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/participant.hpp"
#include "snow_sph/rut.hpp"
#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"

namespace snow_sph {
namespace {

const char* kernel_name(KernelType k) {
  return k == KernelType::cubic ? "cubic" : k == KernelType::quadratic ? "quadratic" : "quintic";
}

nlohmann::json energy_json(const EnergyBalance& e) {
  return {{"kinetic_J", e.kinetic},
          {"internal_J", e.internal},
          {"elastic_stored_J", e.elastic},
          {"plastic_dissipation_J", e.plastic_dissipation},
          {"viscous_dissipation_J", e.viscous_dissipation},
          {"contact_dissipation_J", e.contact_dissipation},
          {"contact_elastic_J", e.contact_elastic},
          {"external_work_J", e.external_work},
          {"deactivated_kinetic_J", e.deactivated_kinetic},
          {"drained_kinetic_J", e.drained_kinetic},
          {"balance_J", e.total() - e.initial_total},
          {"relative_error", e.relative_error()},
          {"note", "energies of the simulated particles and bodies; balance = KE + IE + VD + FD + "
                   "contact - W (Abaqus ETOTAL), relative to max(KE, IE, VD, W)"}};
}

// Surge front along +x: the farthest water particle that still has
// neighbours (isolated drops do not count), plus half a spacing.
double surge_front(const Model& m) {
  const Particles& p = m.particles;
  double front = -1e300;
  for (std::size_t i = 0; i < p.n_real; ++i)
    if (m.materials[p.material[i]].kind == MaterialModel::Kind::water && p.neighbour_count[i] >= 4)
      front = std::max(front, p.x[i]);
  return front + 0.5 * m.settings.spacing - m.container_min[0];
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The rut's cells, row by row (y, then x along the row): those that held
// particles at step 0 and hold some now.
void write_rut_csv(const std::string& path, const RutGrid& grid, const RutSurface& rut) {
  cosim::CsvWriter csv(path, {"x_m", "y_m", "top_z_m", "lowering_m"});
  for (std::size_t j = 0; j < grid.ny; ++j)
    for (std::size_t i = 0; i < grid.nx; ++i) {
      const std::size_t c = i + grid.nx * j;
      if (!std::isnan(rut.lowering_m[c]))
        csv.row({grid.centre_x_m(i), grid.centre_y_m(j), rut.top_z_m[c], rut.lowering_m[c]});
    }
}

// The rut's map (lowering in mm) and, if the grid spans y = 0, the top surface
// along x in the row of cells through y = 0, at step 0 and now. Listed under
// summary "plots" when drawn.
void plot_rut(cosim::RunRecord& record, const std::string& scene, const RutGrid& grid) {
  const std::string csv = record.path("rut_surface.csv");
  cosim::PlotOptions map;
  map.title = scene + ": lowering of the top particle centres [mm]";
  map.x_label = "x [m]", map.y_label = "y [m]", map.colour_label = "mm";
  // Equal scales unless the terrain is a slice (a plane-strain strip), where
  // they would draw a line; its rut is read from the profile.
  map.height_px = 700, map.equal_axes = 5 * std::min(grid.nx, grid.ny) >= std::max(grid.nx, grid.ny);
  if (cosim::plot_png(record.path("rut_surface.png"), map, {{csv, "1:2:($4*1000)", "points pt 5 ps 1.2 palette", ""}}))
    record.summary()["plots"].push_back("rut_surface.png");
  const double rows = std::floor(-grid.y0_m / grid.cell_m);
  if (!(rows >= 0 && rows < static_cast<double>(grid.ny))) return;
  // The row's cells by their centre's y, within a quarter cell (the CSV's 10 digits).
  const std::string y = cosim::number_text(grid.centre_y_m(static_cast<std::size_t>(rows)));
  const std::string near = "abs($2 - (" + y + ")) < " + cosim::number_text(0.25 * grid.cell_m);
  cosim::PlotOptions profile;
  profile.title = scene + ": top particle centres along x at y = " + y + " m";
  profile.x_label = "x [m]", profile.y_label = "z [mm]";
  profile.extra_commands = "set key bottom right\n";  // the undisturbed top runs along the upper edge
  if (cosim::plot_png(record.path("rut_profile.png"), profile,
                      {{csv, "1:(" + near + " ? ($3 + $4)*1000 : 1/0)", "lines lw 2", "step 0"},
                       {csv, "1:(" + near + " ? $3*1000 : 1/0)", "lines lw 2", "end of run"}}))
    record.summary()["plots"].push_back("rut_profile.png");
}

// The SPH terrain under the run skeleton (cosim/participant.hpp): on its own
// (plate sinkage, water column, dam break) or as the terrain of a coupled run,
// whose step reads  advance -> [surface in -> contact -> loads out] -> complete.
class SphRun final : public cosim::Participant {
 public:
  SphRun(const cosim::LoadedScene& loaded, const RunOptions& options)
      : scene_(loaded.message), options_(options), port_(options.exchange) {}

  double initialize(cosim::RunRecord& record) override;
  bool advance() override;
  double time_s() const override { return solver_ ? solver_->time() : 0.0; }
  std::uint64_t steps() const override { return solver_ ? solver_->steps() : 0; }
  void output(cosim::RunRecord& record) override;
  void finalize(cosim::RunRecord& record) override;
  void finish_peers() override {
    if (port_) port_->finish(false, "");
  }
  void abort(const std::string& reason) noexcept override {
    if (!port_) return;
    try {
      port_->finish(true, reason);
    } catch (const std::exception&) {
      // The peers learn of it by their time-out.
    }
  }
  void plots(cosim::RunRecord& record) override;
  // On its own: every checkpoint_interval_s. Coupled: between windows, at the
  // exchanges its peers take theirs (docs/reliability.md, "Coupled runs").
  bool can_checkpoint() const override { return true; }
  bool coupled() const override { return port_ != nullptr; }
  // Exchange n's loads sent and the step after it completed: n + 1 exchanges
  // done, as the coupler and the tyre count them.
  std::optional<std::uint64_t> exchanges_completed() const override {
    return port_ && !stopped_ ? std::optional<std::uint64_t>(exchange_ + 1) : std::nullopt;
  }
  double coupling_window_s() const override { return port_ ? model_->settings.coupling_window_s : 0.0; }
  bool request_checkpoint_stop() override {
    if (!port_) return false;
    port_->request_checkpoint_stop();
    return true;
  }
  std::uint64_t checkpoint_stop_exchange() const override { return port_ ? port_->checkpoint_stop_exchange() : 0; }
  void save(cosim::CheckpointWriter& out) const override;
  void restore(const cosim::CheckpointReader& in) override;

 private:
  // Exchange stage: the surface of exchange n in, its contact with the
  // particles, the loads out. False when the surface's owner ended the run.
  bool exchange_surface(std::uint64_t exchange);
  void record_rows(bool force);
  void write_frame();
  void track_rest();              // after each step: the bodies' rest criterion
  bool bodies_at_rest() const;    // every body with a criterion has met it

  const cosim::scene::Scene& scene_;
  RunOptions options_;
  SurfaceExchange* port_;
  ContactSurface surface_;              // of the current exchange
  std::vector<std::int64_t> compact_scratch_;
  cosim::SurfaceLoads loads_out_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<Solver> solver_;
  cosim::CsvWriter *energy_csv_ = nullptr, *bodies_csv_ = nullptr, *front_csv_ = nullptr, *probe_csv_ = nullptr,
                   *contact_csv_ = nullptr;
  std::unique_ptr<cosim::VtkSeries> vtk_;
  double wall_at_coupling_s_ = 0.0, exchange_wait_s_ = 0.0;
  std::uint64_t exchange_ = 0, windows_ = 0;  // windows_: advance() calls (coupled: windows)
  bool stopped_ = false;
  double dt_min_ = 1e300, dt_max_ = 0.0, dt_sum_ = 0.0;
  std::uint32_t reported_substeps_ = 1;  // the most sub-steps in one window reported on the log
  std::string substeps_cause_;            // what set the terrain's limit at that window
  std::size_t clamped_ = 0;
  double probe_sum_ = 0.0, probe_time_ = 0.0, probe_from_ = 0.0, last_dt_ = 0.0;
  double next_csv_ = 0.0, next_vtk_ = 0.0, csv_interval_ = 0.0, vtk_interval_ = 0.0;
  double floor_x_ = 0.0, floor_y_ = 0.0;
  // Coupled: the terrain's top at step 0 per plan cell, and the deepest
  // penetration of a particle into the surface over the exchanges so far.
  RutGrid rut_grid_;
  double particle_radius_m_ = 0.0, max_penetration_m_ = 0.0;
  // Where and when the deepest was: time, the particle's x, y, z, the facet.
  std::vector<double> deepest_ = std::vector<double>(5, -1.0);
};

double SphRun::initialize(cosim::RunRecord& record) {
  model_ = std::make_unique<Model>(build_model(scene_));
  Model& model = *model_;
  solver_ = std::make_unique<Solver>(model);
  if (port_) {
    // Planned end: the tyre's coupled stages (the tyre ends the run).
    const auto& st = scene_.tyre().stages();
    model.settings.end_time = st.loading_s() + st.rolling_s();
    model.settings.max_steps = 0;
  }
  const auto& sph = scene_.sph();
  nlohmann::json& summary = record.summary();
  summary["particles"] = model.particles.n_real;
  summary["kernel"] = kernel_name(model.kernel.type);
  summary["particle_spacing_m"] = model.settings.spacing;
  summary["smoothing_length_m"] = model.kernel.h;
  summary["symmetry_planes"] = nlohmann::json::array();
  for (const auto& plane : model.planes)
    if (plane.symmetry) summary["symmetry_planes"].push_back(plane.face);
  nlohmann::json materials = nlohmann::json::array();
  for (const auto& mat : model.materials) {
    if (mat.kind == MaterialModel::Kind::water) {
      materials.push_back({{"kind", "water"},
                           {"reference_sound_speed_m_per_s", mat.reference_sound_speed},
                           {"sound_speed_used_m_per_s", mat.eos.c0},
                           {"sound_speed_lowered", mat.sound_speed_lowered},
                           {"tension_limit_Pa", mat.eos.tension_limit},  // 0: none
                           {"valid_density_kg_per_m3", {mat.valid_density_min, mat.valid_density_max}},  // 0: none
                           {"note", mat.sound_speed_lowered
                                        ? "artificial compressibility: sound speed lowered for speed"
                                        : "physical sound speed"}});
    } else {
      materials.push_back({{"kind", "snow"},
                           {"cohesion_Pa", mat.mdpc.cohesion_Pa},
                           {"cap_eccentricity", mat.mdpc.cap_eccentricity}});
    }
  }
  summary["materials"] = materials;
  // A region that is not a whole number of particles is filled short of its
  // max faces: a gap between the snow and a wall unconfines it, and a body
  // started at the region's top falls through the gap (sinkage is measured
  // from the particles' top: RigidBody::surface_z).
  nlohmann::json blocks = nlohmann::json::array();
  for (std::size_t k = 0; k < model.block_lattices.size(); ++k) {
    const BlockLattice& l = model.block_lattices[k];
    const double* a = l.region_max;
    const double* f = l.filled_max;
    blocks.push_back({{"region_max_m", {a[0], a[1], a[2]}}, {"particles_fill_to_m", {f[0], f[1], f[2]}}});
    if (std::max({a[0] - f[0], a[1] - f[1], a[2] - f[2]}) > 1e-9)
      std::fprintf(stderr,
                   "[%s] sph.blocks[%zu]: %s m particles fill the region to (%s, %s, %s) m, short of its max corner "
                   "(%s, %s, %s) m: a spacing that divides the region fills it\n",
                   scene_.name().c_str(), k, cosim::number_text(model.settings.spacing).c_str(),
                   cosim::number_text(f[0]).c_str(), cosim::number_text(f[1]).c_str(), cosim::number_text(f[2]).c_str(),
                   cosim::number_text(a[0]).c_str(), cosim::number_text(a[1]).c_str(), cosim::number_text(a[2]).c_str());
  }
  summary["blocks"] = blocks;
  probe_from_ = model.settings.end_time - sph.probes().average_last_s();
  csv_interval_ = scene_.output().csv_interval_s();
  vtk_interval_ = options_.write_vtk ? scene_.output().vtk_interval_s() : 0.0;
  floor_x_ = 0.5 * (model.container_min[0] + model.container_max[0]);
  floor_y_ = 0.5 * (model.container_min[1] + model.container_max[1]);

  if (port_) {
    const Particles& p = model.particles;
    rut_grid_ = make_rut_grid(p.n_real, p.x.data(), p.y.data(), p.z.data(), model.settings.spacing);
    const auto& c = scene_.coupling();
    SurfaceContactParameters contact;
    contact.particle_radius_m = 0.5 * model.settings.spacing;
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
    const double agreed = port_->connect(model.settings.cfl * limit, record.resume_step());
    if (!(agreed > 0) || agreed > limit)
      throw cosim::Error("the agreed coupled time step " + cosim::number_text(agreed) +
                         " s is above the terrain's stable limit " + cosim::number_text(limit) + " s");
    model.settings.coupling_window_s = agreed;
    wall_at_coupling_s_ = record.wall_s();
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
  solver_->initialise();
  energy_csv_ = &record.series("energy.csv", {"time_s", "kinetic_J", "internal_J", "elastic_stored_J",
                                              "plastic_dissipation_J", "viscous_dissipation_J",
                                              "contact_dissipation_J", "external_work_J", "energy_relative_error"});
  if (!model.bodies.empty()) {
    std::vector<std::string> cols{"time_s"};
    for (const auto& b : model.bodies)
      for (const char* c : {"_z_m", "_displacement_m", "_velocity_z_m_per_s", "_contact_force_z_N",
                            "_applied_force_z_N"})
        cols.push_back(b.name + c);
    bodies_csv_ = &record.series("bodies.csv", cols);
  }
  if (sph.probes().surge_front()) front_csv_ = &record.series("front.csv", {"time_s", "front_m"});
  if (sph.probes().floor_pressure())
    probe_csv_ = &record.series("floor_pressure.csv", {"time_s", "floor_pressure_Pa"});
  if (vtk_interval_ > 0) vtk_ = std::make_unique<cosim::VtkSeries>(record.path("vtk"), "particles");
  record_rows(true);
  if (vtk_) write_frame(), next_vtk_ = solver_->time() + vtk_interval_;
  return model.settings.end_time;
}

bool SphRun::exchange_surface(std::uint64_t exchange) {
  const auto t0 = std::chrono::steady_clock::now();
  const cosim::SurfaceState* state = port_->surface(exchange);
  exchange_wait_s_ += seconds_since(t0);
  if (state) assemble_contact_surface(port_->topology(), *state, surface_, compact_scratch_);
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
  port_->send_loads(loads_out_);
  exchange_wait_s_ += seconds_since(t1);
  exchange_ = exchange;
  return true;
}

bool SphRun::advance() {
  const Settings& settings = model_->settings;
  if (stopped_) return false;
  if (!port_ && !(solver_->time() < settings.end_time - 1e-12 &&
                  (settings.max_steps == 0 || solver_->steps() < settings.max_steps)))
    return false;
  if (!port_ && bodies_at_rest()) return false;
  const StepStats st = solver_->advance();
  ++windows_;
  if (st.substeps > reported_substeps_) {
    // The first sub-stepped window and every new most in one window, with what
    // sets the limit after it (a sub-stepping run's cost is this cause's).
    reported_substeps_ = st.substeps;
    substeps_cause_ = solver_->limit_cause();
    std::fprintf(stderr,
                 "[%s] t = %s s: the terrain's stable limit (smallest %s s) is below the coupling window %s s; "
                 "%u sub-steps in this window, the most so far (now set by %s; docs/coupling.md)\n",
                 scene_.name().c_str(), cosim::number_text(solver_->time()).c_str(),
                 cosim::number_text(solver_->smallest_limit_dt()).c_str(), cosim::number_text(st.dt).c_str(),
                 st.substeps, substeps_cause_.c_str());
  }
  if (port_ && !exchange_surface(exchange_ + 1)) {
    // The surface's owner ended the run during this step.
    solver_->complete_step();
    stopped_ = true;
    return false;
  }
  solver_->complete_step();
  track_rest();
  dt_min_ = std::min(dt_min_, st.dt), dt_max_ = std::max(dt_max_, st.dt), dt_sum_ += st.dt;
  clamped_ += st.clamped;
  last_dt_ = st.dt;
  if (!solver_->finite())
    throw cosim::Error("the solution became non-finite (NaN/Inf) at step " + std::to_string(solver_->steps()) +
                       ", t = " + cosim::number_text(solver_->time()) + " s");
  return true;
}

void SphRun::save(cosim::CheckpointWriter& out) const {
  solver_->save(out);
  out.put("run.doubles", std::vector<double>{dt_min_, dt_max_, dt_sum_, probe_sum_, probe_time_, last_dt_, next_csv_,
                                             next_vtk_, max_penetration_m_, deepest_[0], deepest_[1], deepest_[2],
                                             deepest_[3], deepest_[4]});
  out.put("run.counters", std::vector<std::uint64_t>{exchange_, windows_, clamped_, stopped_ ? 1u : 0u});
  out.put("run.vtk_frame_times", vtk_ ? vtk_->frame_times() : std::vector<double>{});
}

void SphRun::restore(const cosim::CheckpointReader& in) {
  solver_->restore(in);
  const auto d = in.get<double>("run.doubles", 14);
  dt_min_ = d[0], dt_max_ = d[1], dt_sum_ = d[2], probe_sum_ = d[3], probe_time_ = d[4], last_dt_ = d[5];
  next_csv_ = d[6], next_vtk_ = d[7], max_penetration_m_ = d[8];
  deepest_.assign(d.begin() + 9, d.end());
  const auto c = in.get<std::uint64_t>("run.counters", 4);
  exchange_ = c[0], windows_ = c[1], clamped_ = c[2], stopped_ = c[3] != 0;
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

void SphRun::output(cosim::RunRecord&) {
  record_rows(false);
  if (probe_csv_) {
    const double pr = solver_->pressure_at(floor_x_, floor_y_, model_->container_min[2]);
    if ((solver_->steps() & 63u) == 0) probe_csv_->row({solver_->time(), pr});
    if (solver_->time() >= probe_from_) probe_sum_ += pr * last_dt_, probe_time_ += last_dt_;
  }
  if (vtk_ && solver_->time() + 1e-12 >= next_vtk_) write_frame(), next_vtk_ += vtk_interval_;
}

void SphRun::write_frame() {
  const Particles& p = model_->particles;
  const std::size_t n = p.n_real;
  std::vector<double> id(p.id.begin(), p.id.begin() + n), mat(n), von_mises(n), cap_pressure(n);
  for (std::size_t i = 0; i < n; ++i) {
    mat[i] = p.material[i];
    von_mises[i] = von_mises_stress_Pa(p, i);
    // The cap's hydrostatic yield pressure p_b(eps_vol_pl): how far the snow has
    // been compacted (Abaqus 23.3.2); 0 for water.
    const MaterialModel& material = model_->materials[p.material[i]];
    cap_pressure[i] = material.kind == MaterialModel::Kind::snow
                          ? material.mdpc.cap_hydrostatic_yield_Pa(p.eps_vol_pl[i]) : 0.0;
  }
  vtk_->write(solver_->time(), n, p.x.data(), p.y.data(), p.z.data(),
              {{"density_kg_per_m3", p.density.data()},
               {"pressure_Pa", p.pressure.data()},
               {"von_mises_stress_Pa", von_mises.data()},
               {"volumetric_plastic_strain", p.eps_vol_pl.data()},
               {"cap_hydrostatic_yield_pressure_Pa", cap_pressure.data()},
               {"material", mat.data()},
               {"id", id.data()}},
              {{"velocity_m_per_s", p.vx.data(), p.vy.data(), p.vz.data()}});
}

void SphRun::record_rows(bool force) {
  if (!energy_csv_) return;
  const double t = solver_->time();
  if (!force && t + 1e-15 < next_csv_) return;
  next_csv_ = t + csv_interval_;
  const EnergyBalance& e = solver_->energy();
  energy_csv_->row({t, e.kinetic, e.internal, e.elastic, e.plastic_dissipation, e.viscous_dissipation,
                    e.contact_dissipation, e.external_work, e.relative_error()});
  if (bodies_csv_) {
    std::vector<double> row{t};
    for (const auto& b : model_->bodies)
      row.insert(row.end(), {b.z, b.z0 - b.z, b.vz, b.contact_force_z_domain * b.symmetry_factor,
                             b.applied_force_z_now(t)});
    bodies_csv_->row(row);
  }
  if (front_csv_) front_csv_->row({t, surge_front(*model_)});
  if (contact_csv_) {
    const SurfaceContactResult& l = solver_->surface_loads();
    double area = 0.0, in_contact = 0.0;
    for (double a : l.facet_contact_area_m2) area += a;
    for (auto c : l.particles_in_contact) in_contact += c;
    contact_csv_->row({t, l.total_fx_N, l.total_fy_N, l.total_fz_N, area, in_contact,
                       static_cast<double>(solver_->drained_particles()), l.max_penetration_m, l.deepest_x_m,
                       l.deepest_z_m, static_cast<double>(l.deepest_facet),
                       static_cast<double>(l.particles_behind_surface), l.particle_reach_z_m});
  }
}

void SphRun::finalize(cosim::RunRecord& record) {
  if (!solver_) return;  // the model was never built
  const Model& model = *model_;
  const Solver& solver = *solver_;
  const Particles& p = model.particles;
  record_rows(true);
  if (vtk_ && vtk_->frames() > 0 && next_vtk_ - vtk_interval_ < solver.time() - 1e-12) write_frame();
  nlohmann::json& summary = record.summary();
  const double wall = record.wall_s();
  const auto steps = solver.steps();
  summary["dt_s"] = {{"min", windows_ ? dt_min_ : 0.0}, {"mean", windows_ ? dt_sum_ / windows_ : 0.0}, {"max", dt_max_},
                     {"smallest_stability_limit", solver.smallest_limit_dt()}};
  summary["energy"] = energy_json(solver.energy());
  summary["wall_clamps"] = clamped_;
  summary["neighbour_list_rebuilds"] = solver.rebuilds();
  const double inter = static_cast<double>(solver.interactions());
  summary["performance"] = {
      {"particle_steps_per_s", wall > 0 ? p.n_real * static_cast<double>(steps) / wall : 0.0},
      {"mean_neighbours", steps && p.n_real ? inter / (static_cast<double>(steps) * p.n_real) : 0.0},
      {"interactions_per_s", wall > 0 ? inter / wall : 0.0},
      {"note", "interactions: neighbour pairs within the support per step, counted from both "
               "sides as DualSPHysics counts them (each is visited twice a step: rates, forces)"}};
  if (port_) {
    // Stepping only (model building and the start handshake excluded).
    const double compute = wall - wall_at_coupling_s_ - exchange_wait_s_;
    auto& perf = summary["performance"];
    perf["coupled_wall_s"] = wall - wall_at_coupling_s_;
    perf["exchange_wait_s"] = exchange_wait_s_;
    perf["compute_s"] = compute;
    perf["compute_s_per_step"] = windows_ ? compute / windows_ : 0.0;  // per window
    perf["coupling_window_s"] = summary["coupled_dt_s"];
    // Windows in which the terrain's own limit fell below the window (docs/coupling.md).
    perf["terrain_substepped_windows"] = solver.substepped_windows();
    perf["terrain_most_substeps_per_window"] = solver.most_substeps();
    if (!substeps_cause_.empty()) perf["terrain_most_substeps_cause"] = substeps_cause_;
    perf["active_particle_share"] = solver.mean_active_share();
    perf["held_load_window_limit_s"] = solver.held_load_limit_dt();
    perf["smallest_terrain_stability_limit_s"] = solver.smallest_limit_dt();
    perf["active_domain_margin_m"] = scene_.coupling().active_domain_margin_m();
    perf["active_domain_wake_limit_m"] = scene_.coupling().active_domain_wake_limit_m();
    const double* impulse = solver.surface_impulse_Ns();
    summary["surface_impulse_on_particles_Ns"] = {impulse[0], impulse[1], impulse[2]};
  }
  nlohmann::json& results = record.results();
  if (port_ && particle_radius_m_ > 0.0) {
    // The rut and the deepest penetration (docs/outputs.md), for every coupled run.
    const RutSurface rut = rut_surface(rut_grid_, p.n_real, p.x.data(), p.y.data(), p.z.data());
    write_rut_csv(record.path("rut_surface.csv"), rut_grid_, rut);
    results["rut_depth_m"] = rut.rut_depth_m;
    results["max_penetration_m"] = max_penetration_m_;
    if (deepest_[4] >= 0)  // where a particle went deepest (terrain_contact.csv: at each row's exchange)
      results["deepest_contact"] = {{"time_s", deepest_[0]}, {"particle_x_m", deepest_[1]},
                                    {"particle_y_m", deepest_[2]}, {"particle_z_m", deepest_[3]},
                                    {"facet", static_cast<std::int64_t>(deepest_[4])}};
    results["particle_radius_m"] = particle_radius_m_;
    // Water squeezed into films thinner than half a particle (docs/water.md).
    double water_kg = 0.0;
    for (std::size_t i = 0; i < p.n_real; ++i)
      if (model.materials[p.material[i]].kind == MaterialModel::Kind::water) water_kg += p.mass[i];
    if (water_kg > 0.0 || solver.drained_particles() > 0) {
      results["drained_water_particles"] = solver.drained_particles();
      results["drained_water_mass_kg"] = solver.drained_mass_kg();
      results["drained_water_share"] = solver.drained_mass_kg() / (water_kg + solver.drained_mass_kg());
      results["water_density_out_of_range_particles"] = solver.density_out_particles();  // among the drained
    }
    if (scene_.coupling().place_terrain_around_loaded_tyre()) {  // where the tyre stood when the terrain was placed
      results["particles_removed_inside_the_tyre"] = solver.displaced_particles();
      results["mass_removed_inside_the_tyre_kg"] = solver.displaced_mass_kg();
    }
  }
  for (const auto& b : model.bodies) {
    results[b.name + "_displacement_m"] = b.z0 - b.z;
    if (std::isfinite(b.surface_z)) {
      results[b.name + "_sinkage_m"] = b.surface_z - b.z;  // below the snow's surface at the start
      results[b.name + "_snow_surface_z_m"] = b.surface_z;
    }
    results[b.name + "_velocity_z_m_per_s"] = b.vz;
    results[b.name + "_contact_force_z_N"] = b.contact_force_z_domain * b.symmetry_factor;
    results[b.name + "_applied_force_z_N"] = b.applied_force_z_now(solver.time());
    if (b.rest_speed > 0.0) {
      const bool rested = b.at_rest(solver.time());
      results[b.name + "_at_rest"] = rested;
      results[b.name + "_rest_speed_criterion_m_per_s"] = b.rest_speed;
      if (rested) results[b.name + "_came_to_rest_at_s"] = b.slow_since_s;
    }
  }
  const auto& sph = scene_.sph();
  if (sph.probes().floor_pressure()) {
    double weight = 0.0;
    for (std::size_t i = 0; i < p.n_real; ++i) weight += p.mass[i];
    weight *= std::abs(model.settings.gravity[2]);
    const double area = (model.container_max[0] - model.container_min[0]) *
                        (model.container_max[1] - model.container_min[1]);
    const double hydro = weight / area;
    const double bottom = probe_time_ > 0 ? probe_sum_ / probe_time_ : 0.0;
    results["bottom_pressure_Pa"] = bottom;
    results["hydrostatic_pressure_Pa"] = hydro;
    results["bottom_pressure_relative_error"] = (bottom - hydro) / hydro;
    results["note_hydrostatic"] = "rho g H as the column's weight per floor area";
  }
  if (sph.probes().surge_front()) {
    const auto& region = sph.blocks(0).region();
    results["column_width_m"] = region.max().x() - region.min().x();
    results["column_height_m"] = region.max().z() - region.min().z();
    results["final_front_m"] = surge_front(model);
  }
}

void SphRun::plots(cosim::RunRecord& record) {
  if (!energy_csv_) return;
  const std::string name = scene_.name();
  if (port_ && record.results().contains("rut_depth_m")) plot_rut(record, name, rut_grid_);
  record.plot("energy.csv", "energy.png", 1, {{2, "kinetic"}, {3, "internal"}, {6, "viscous"}, {8, "external work"}},
              name + ": energy", "time [s]", "energy [J]");
  if (bodies_csv_)
    record.plot("bodies.csv", "bodies.png", 1, {{3, model_->bodies[0].name + " displacement"}},
                name + ": " + model_->bodies[0].name + " displacement", "time [s]", "displacement [m]");
  if (front_csv_)
    record.plot("front.csv", "front.png", 1, {{2, "surge front"}}, name + ": surge front", "time [s]",
                "front position [m]");
  if (probe_csv_)
    record.plot("floor_pressure.csv", "floor_pressure.png", 1, {{2, "floor pressure"}}, name + ": floor pressure",
                "time [s]", "pressure [Pa]");
}

}  // namespace

nlohmann::json run_scene(const cosim::LoadedScene& loaded, const RunOptions& options) {
  cosim::RunRecord record(loaded, options.out_dir, "snow_sph", options.restart);
  if (options.restart_at) record.restart_at(*options.restart_at);
  SphRun run(loaded, options);
  return cosim::run_participant(run, record, loaded.message.name(), options.quiet);
}

}  // namespace snow_sph
