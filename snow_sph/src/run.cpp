#include "snow_sph/run.hpp"

#include <cmath>
#include <memory>

#include "cosim/error.hpp"
#include "cosim/interrupt.hpp"
#include "cosim/outputs.hpp"
#include "cosim/parallel.hpp"
#include "cosim/progress.hpp"
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

}  // namespace

nlohmann::json run_scene(const cosim::LoadedScene& loaded, const RunOptions& options) {
  const auto& scene = loaded.message;
  cosim::make_folder(options.out_dir);
  const std::string out = options.out_dir;
  nlohmann::json summary = {{"scene", scene.name()},
                            {"scene_file", loaded.file},
                            {"revision", cosim::source_revision()},
                            {"participants", {"snow_sph"}},
                            {"threads", cosim::max_threads()},
                            {"status", "running"}};
  nlohmann::json overrides = nlohmann::json::object();
  for (const auto& [k, v] : loaded.overrides) overrides[k] = v;
  summary["overrides"] = overrides;

  Model model = build_model(scene);
  Solver solver(model);
  const bool coupled = options.exchange != nullptr;
  if (coupled) {
    // Planned end: the tyre's coupled stages (the tyre ends the run).
    const auto& st = scene.tyre().stages();
    model.settings.end_time = st.loading_s() + st.rolling_s();
    model.settings.max_steps = 0;
  }
  cosim::Progress progress(scene.name(), model.settings.end_time, options.quiet);
  const auto& sph = scene.sph();

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

  std::unique_ptr<cosim::CsvWriter> energy_csv, bodies_csv, front_csv, probe_csv, contact_csv;
  double coupled_from_s = 0.0;  // wall time when the coupled stepping began
  std::unique_ptr<cosim::VtkSeries> vtk;
  double dt_min = 1e300, dt_max = 0.0, dt_sum = 0.0;
  std::size_t clamped = 0;
  double probe_sum = 0.0, probe_time = 0.0;
  const double t_end = model.settings.end_time;
  const double probe_from = t_end - sph.probes().average_last_s();
  double next_csv = 0.0, next_vtk = 0.0;
  const double csv_interval = scene.output().csv_interval_s();
  const double vtk_interval = options.write_vtk ? scene.output().vtk_interval_s() : 0.0;
  const Particles& p = model.particles;

  auto write_vtk = [&]() {
    if (!vtk) return;
    const std::size_t n = p.n_real;
    std::vector<double> id(p.id.begin(), p.id.begin() + n), mat(n);
    for (std::size_t i = 0; i < n; ++i) mat[i] = p.material[i];
    vtk->write(solver.time(), n, p.x.data(), p.y.data(), p.z.data(),
               {{"density_kg_per_m3", p.density.data()},
                {"pressure_Pa", p.pressure.data()},
                {"volumetric_plastic_strain", p.eps_vol_pl.data()},
                {"material", mat.data()},
                {"id", id.data()}},
               {{"velocity_m_per_s", p.vx.data(), p.vy.data(), p.vz.data()}});
  };
  auto record = [&](bool force) {
    const double t = solver.time();
    if (!force && t + 1e-15 < next_csv) return;
    next_csv = t + csv_interval;
    const EnergyBalance& e = solver.energy();
    energy_csv->row({t, e.kinetic, e.internal, e.elastic, e.plastic_dissipation,
                     e.viscous_dissipation, e.contact_dissipation, e.external_work,
                     e.relative_error()});
    if (bodies_csv) {
      std::vector<double> row{t};
      for (const auto& b : model.bodies) {
        row.insert(row.end(), {b.z, b.z0 - b.z, b.vz, b.contact_force_z_domain * b.symmetry_factor,
                               b.applied_force_z_now(t)});
      }
      bodies_csv->row(row);
    }
    if (front_csv) front_csv->row({t, surge_front(model)});
    if (contact_csv) {
      const SurfaceLoads& l = solver.surface_loads();
      double area = 0.0, in_contact = 0.0;
      for (double a : l.facet_contact_area_m2) area += a;
      for (auto c : l.particles_in_contact) in_contact += c;
      contact_csv->row({t, l.total_fx_N, l.total_fy_N, l.total_fz_N, area, in_contact});
    }
  };

  try {
    if (coupled) {
      const auto& c = scene.coupling();
      SurfaceContactParameters contact;
      contact.particle_radius_m = 0.5 * model.settings.spacing;
      contact.stiffness_N_per_m = model.settings.contact_stiffness *
                                  (c.contact_stiffness_scale() > 0 ? c.contact_stiffness_scale() : 1.0);
      solver.couple(options.exchange, contact);
      // A particle still moving faster than 1 cm/s stays in the active domain
      // (docs/coupling.md): the resting terrain is at rest to well below that.
      solver.set_active_domain(c.active_domain_margin_m(), 0.01);
      solver.prepare();  // sound speeds and accelerations of the first step
      const double limit = solver.stability_limit_dt();
      const double agreed = options.exchange->connect(model.settings.cfl * limit);
      if (!(agreed > 0) || agreed > limit)
        throw cosim::Error("the agreed coupled time step " + cosim::number_text(agreed) +
                           " s is above the terrain's stable limit " + cosim::number_text(limit) + " s");
      model.settings.fixed_dt = agreed;
      coupled_from_s = progress.elapsed_s();
      summary["coupled_dt_s"] = agreed;
      summary["surface_contact"] = {{"particle_radius_m", contact.particle_radius_m},
                                    {"stiffness_N_per_m", contact.stiffness_N_per_m},
                                    {"damping_ratio", contact.damping_ratio}};
      contact_csv = std::make_unique<cosim::CsvWriter>(
          out + "/terrain_contact.csv",
          std::vector<std::string>{"time_s", "force_on_surface_x_N", "force_on_surface_y_N", "force_on_surface_z_N",
                                   "contact_area_m2", "particles_in_contact"});
    }
    solver.initialise();
    std::vector<std::string> energy_cols{"time_s", "kinetic_J", "internal_J", "elastic_stored_J",
                                         "plastic_dissipation_J", "viscous_dissipation_J",
                                         "contact_dissipation_J", "external_work_J",
                                         "energy_relative_error"};
    energy_csv = std::make_unique<cosim::CsvWriter>(out + "/energy.csv", energy_cols);
    if (!model.bodies.empty()) {
      std::vector<std::string> cols{"time_s"};
      for (const auto& b : model.bodies)
        for (const char* c : {"_z_m", "_displacement_m", "_velocity_z_m_per_s",
                              "_contact_force_z_N", "_applied_force_z_N"})
          cols.push_back(b.name + c);
      bodies_csv = std::make_unique<cosim::CsvWriter>(out + "/bodies.csv", cols);
    }
    if (sph.probes().surge_front())
      front_csv = std::make_unique<cosim::CsvWriter>(out + "/front.csv",
                                                     std::vector<std::string>{"time_s", "front_m"});
    if (sph.probes().floor_pressure())
      probe_csv = std::make_unique<cosim::CsvWriter>(
          out + "/floor_pressure.csv", std::vector<std::string>{"time_s", "floor_pressure_Pa"});
    if (vtk_interval > 0) vtk = std::make_unique<cosim::VtkSeries>(out + "/vtk", "particles");
    record(true);
    if (vtk) write_vtk(), next_vtk = vtk_interval;
    const double floor_x = 0.5 * (model.container_min[0] + model.container_max[0]);
    const double floor_y = 0.5 * (model.container_min[1] + model.container_max[1]);
    while (coupled || (solver.time() < t_end - 1e-12 &&
                       (model.settings.max_steps == 0 || solver.steps() < model.settings.max_steps))) {
      if (solver.stopped()) break;
      const StepStats st = solver.step();
      if (st.stopped) break;
      dt_min = std::min(dt_min, st.dt), dt_max = std::max(dt_max, st.dt), dt_sum += st.dt;
      clamped += st.clamped;
      if (cosim::interrupt_requested())
        throw cosim::Error("interrupted by a signal at step " + std::to_string(solver.steps()) +
                           ", t = " + cosim::number_text(solver.time()) + " s");
      if (!solver.finite())
        throw cosim::Error("the solution became non-finite (NaN/Inf) at step " +
                           std::to_string(solver.steps()) + ", t = " + cosim::number_text(solver.time()) + " s");
      record(false);
      if (probe_csv) {
        const double pr = solver.pressure_at(floor_x, floor_y, model.container_min[2]);
        if ((solver.steps() & 63u) == 0) probe_csv->row({solver.time(), pr});
        if (solver.time() >= probe_from) probe_sum += pr * st.dt, probe_time += st.dt;
      }
      if (vtk && solver.time() + 1e-12 >= next_vtk) write_vtk(), next_vtk += vtk_interval;
      progress.update(solver.time(), solver.steps());
    }
    record(true);
    if (vtk && vtk->frames() > 0 && next_vtk - vtk_interval < solver.time() - 1e-12) write_vtk();
    progress.finish(solver.time(), solver.steps());
    summary["status"] = "completed";
    if (coupled) options.exchange->finish(false, "");
  } catch (const std::exception& e) {
    summary["status"] = "failed";
    summary["error"] = e.what();
    if (coupled) {
      try {
        options.exchange->finish(true, e.what());
      } catch (const std::exception&) {
        // The peers learn of it by their time-out.
      }
    }
  }

  const double wall = progress.elapsed_s();
  const auto steps = solver.steps();
  summary["wall_time_s"] = wall;
  summary["sim_time_s"] = solver.time();
  summary["steps"] = steps;
  summary["dt_s"] = {{"min", steps ? dt_min : 0.0}, {"mean", steps ? dt_sum / steps : 0.0}, {"max", dt_max},
                     {"smallest_stability_limit", solver.smallest_limit_dt()}};
  summary["energy"] = energy_json(solver.energy());
  summary["wall_clamps"] = clamped;
  summary["neighbour_list_rebuilds"] = solver.rebuilds();
  const double inter = static_cast<double>(solver.interactions());
  summary["performance"] = {
      {"particle_steps_per_s", wall > 0 ? p.n_real * static_cast<double>(steps) / wall : 0.0},
      {"mean_neighbours", steps && p.n_real ? inter / (static_cast<double>(steps) * p.n_real) : 0.0},
      {"interactions_per_s", wall > 0 ? inter / wall : 0.0},
      {"note", "interactions: neighbour pairs within the support per step, counted from both "
               "sides as DualSPHysics counts them (each is visited twice a step: rates, forces)"}};
  if (coupled) {
    // Stepping only (model building and the start handshake excluded).
    const double compute = wall - coupled_from_s - solver.exchange_wait_s();
    summary["performance"]["coupled_wall_s"] = wall - coupled_from_s;
    summary["performance"]["exchange_wait_s"] = solver.exchange_wait_s();
    summary["performance"]["compute_s"] = compute;
    summary["performance"]["compute_s_per_step"] = steps ? compute / steps : 0.0;
    summary["performance"]["coupling_window_s"] = summary["coupled_dt_s"];
    summary["performance"]["active_particle_share"] = solver.mean_active_share();
    summary["performance"]["held_load_window_limit_s"] = solver.held_load_limit_dt();
    summary["performance"]["smallest_terrain_stability_limit_s"] = solver.smallest_limit_dt();
    summary["performance"]["active_domain_margin_m"] = scene.coupling().active_domain_margin_m();
    const double* impulse = solver.surface_impulse_Ns();
    summary["surface_impulse_on_particles_Ns"] = {impulse[0], impulse[1], impulse[2]};
  }

  nlohmann::json results = nlohmann::json::object();
  for (const auto& b : model.bodies) {
    results[b.name + "_displacement_m"] = b.z0 - b.z;
    results[b.name + "_velocity_z_m_per_s"] = b.vz;
    results[b.name + "_contact_force_z_N"] = b.contact_force_z_domain * b.symmetry_factor;
    results[b.name + "_applied_force_z_N"] = b.applied_force_z_now(solver.time());
  }
  if (sph.probes().floor_pressure()) {
    double weight = 0.0;
    for (std::size_t i = 0; i < p.n_real; ++i) weight += p.mass[i];
    weight *= std::abs(model.settings.gravity[2]);
    const double area = (model.container_max[0] - model.container_min[0]) *
                        (model.container_max[1] - model.container_min[1]);
    const double hydro = weight / area;
    const double bottom = probe_time > 0 ? probe_sum / probe_time : 0.0;
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
  summary["results"] = results;
  // Pictures a person would rather look at than read.
  try {
    energy_csv.reset(), bodies_csv.reset(), front_csv.reset(), probe_csv.reset(), contact_csv.reset();
    nlohmann::json plots = nlohmann::json::array();
    if (cosim::plot_csv(out + "/energy.csv", out + "/energy.png", 1,
                        {{2, "kinetic"}, {3, "internal"}, {6, "viscous"}, {8, "external work"}},
                        scene.name() + ": energy", "time [s]", "energy [J]"))
      plots.push_back("energy.png");
    if (!model.bodies.empty() &&
        cosim::plot_csv(out + "/bodies.csv", out + "/bodies.png", 1, {{3, model.bodies[0].name + " displacement"}},
                        scene.name() + ": " + model.bodies[0].name + " displacement", "time [s]", "displacement [m]"))
      plots.push_back("bodies.png");
    if (sph.probes().surge_front() &&
        cosim::plot_csv(out + "/front.csv", out + "/front.png", 1, {{2, "surge front"}},
                        scene.name() + ": surge front", "time [s]", "front position [m]"))
      plots.push_back("front.png");
    if (sph.probes().floor_pressure() &&
        cosim::plot_csv(out + "/floor_pressure.csv", out + "/floor_pressure.png", 1, {{2, "floor pressure"}},
                        scene.name() + ": floor pressure", "time [s]", "pressure [Pa]"))
      plots.push_back("floor_pressure.png");
    summary["plots"] = plots;
  } catch (const std::exception&) {
    // Plots are a convenience; the numbers are already on disk.
  }
  cosim::write_json(out + "/summary.json", summary);
  if (summary["status"] == "failed") throw cosim::Error(summary["error"].get<std::string>());
  return summary;
}

}  // namespace snow_sph
