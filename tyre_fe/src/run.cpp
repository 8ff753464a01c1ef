#include "tyre_fe/run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cosim/coupling_window.hpp"
#include "cosim/error.hpp"
#include "cosim/interrupt.hpp"
#include "cosim/outputs.hpp"
#include "cosim/ramp.hpp"
#include "cosim/parallel.hpp"
#include "cosim/progress.hpp"
#include "tyre_fe/model3d.hpp"
#include "tyre_fe/outputs.hpp"
#include "tyre_fe/scene.hpp"
#include "tyre_fe/solver3d.hpp"

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
double free_radius(const Model3d& m, const State3d& s) {
  double lowest = 1e30;
  for (int n : m.contact_nodes) lowest = std::min(lowest, s.z[n]);
  return s.rim.z - lowest;
}

// The wheel load, speed and drive torque ramp in with zero rate at both ends.
double smooth_ramp(double t, double ramp) { return cosim::ramp(cosim::RampCurve::smoothstep, t, ramp); }

nlohmann::json energy_json(const Energies& e) {
  return {{"kinetic_J", e.kinetic_J},           {"internal_J", e.internal_J},
          {"hourglass_J", e.hourglass_J},       {"external_work_J", e.external_work_J},
          {"damping_work_J", e.damping_work_J}, {"contact_work_J", e.contact_work_J},
          {"initial_J", e.initial_J},           {"relative_error", e.balance_error()},
          {"note", "balance = KE + IE - E0 - W_ext - W_damping - W_contact, relative to max(IE, KE, |W_ext|)"}};
}

}  // namespace

nlohmann::json run_tyre_scene(const cosim::LoadedScene& loaded, const RunOptions& options) {
  const sc::Scene& scene = loaded.message;
  const sc::TyreModel& t = scene.tyre();
  cosim::make_folder(options.out_dir);
  const std::string out = options.out_dir;
  nlohmann::json summary = {{"scene", scene.name()},         {"scene_file", loaded.file},
                            {"revision", cosim::source_revision()}, {"participants", {"tyre_fe"}},
                            {"threads", cosim::max_threads()}, {"status", "running"}};
  nlohmann::json overrides = nlohmann::json::object();
  for (const auto& [k, v] : loaded.overrides) overrides[k] = v;
  summary["overrides"] = overrides;
  nlohmann::json results = nlohmann::json::object();
  cosim::Progress* progress_ptr = nullptr;
  std::unique_ptr<cosim::CsvWriter> csv;
  std::uint64_t steps = 0;
  double sim_time = 0.0;
  const auto start = std::chrono::steady_clock::now();
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto write_summary = [&](const std::string& status) {
    summary["status"] = status;
    summary["results"] = results;
    summary["wall_time_s"] = wall();
    summary["sim_time_s"] = sim_time;
    summary["steps"] = steps;
    cosim::write_json(out + "/summary.json", summary);
  };
  try {
    const TyreSetup setup = tyre_setup(loaded);
    summary["tyre_size"] = setup.size_designation;
    summary["materials_source"] = setup.materials_source;
    summary["bulk_to_shear_ratio"] = setup.bulk_to_shear_ratio;
    const CrossSection section = make_section(setup);
    Mesh3D mesh = revolve(section, setup.pattern);
    summary["cross_section"] = {{"nodes", section.nodes.size()}, {"elements", section.quads.size()}};
    nlohmann::json tags = nlohmann::json::object();
    for (int k = 0; k < kSurfaceTagCount; ++k) tags[surface_tag_name(static_cast<SurfaceTag>(k))] = 0;
    for (const auto& f : mesh.facets) tags[surface_tag_name(f.tag)] = tags[surface_tag_name(f.tag)].get<int>() + 1;
    results["nodes"] = mesh.nodes.size();
    results["elements"] = mesh.hexes.size();
    results["facets"] = mesh.facets.size();
    results["facets_by_tag"] = tags;
    summary["elements"] = mesh.hexes.size();
    if (options.write_vtk || options.mesh_only || t.mesh_only()) {
      write_cross_section_vtk(out + "/cross_section.vtk", section, section.nodes);
      write_mesh_vtk(out + "/mesh3d.vtk", mesh, mesh.nodes);
      write_facets_vtk(out + "/surface.vtk", mesh, mesh.nodes);
    }
    // The model (masses, stable step) is cheap to build: mesh-only runs report the step too.
    Model3dOptions mo;
    mo.time_step_safety = scene.time().cfl() > 0 ? scene.time().cfl() : 0.8;
    mo.mass_scaling_target_dt_s = t.mass_scaling_target_dt_s();
    Model3d model = build_model3d(std::move(mesh), setup.materials, section, mo);
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
    if (options.mesh_only || t.mesh_only()) {
      write_summary("completed");
      return summary;
    }

    // 1. Inflation in the axisymmetric model.
    AxisymLoadCase inflation;
    inflation.pressure_Pa = t.inflation_pressure_pa();
    inflation.fixed_nodes = section.rim_nodes;
    if (t.stages().inflation_tolerance() > 0) inflation.tolerance = t.stages().inflation_tolerance();
    if (!options.quiet) std::fprintf(stderr, "[%s] inflating the cross-section to %.0f kPa\n", scene.name().c_str(), inflation.pressure_Pa / 1e3);
    const AxisymResult axi = solve_axisym(section, setup.materials, inflation);
    if (!axi.converged)
      throw cosim::Error("axisymmetric inflation did not come to rest in " + std::to_string(axi.steps) +
                         " steps (residual ratio " + cosim::number_text(axi.residual_ratio) + ")");
    const int centre = section.tread_centre_node;
    const double r0 = section.nodes[centre][0];
    results["axisym_radial_growth_m"] = axi.nodes[centre][0] - r0;
    results["axisym_steps"] = axi.steps;
    results["axisym_residual_ratio"] = axi.residual_ratio;
    write_cross_section_vtk(out + "/cross_section_inflated.vtk", section, axi.nodes);

    // 2. Revolve and transfer; the 3D model starts inflated and at rest.
    double dt = model.stable_dt_s;
    if (scene.time().fixed_dt_s() > 0) {
      if (scene.time().fixed_dt_s() > model.stable_dt_s)
        throw cosim::Error(loaded.locator().child("time").where("fixed_dt_s") + ": fixed time step " +
                           cosim::number_text(scene.time().fixed_dt_s()) + " s is above the stable limit " +
                           cosim::number_text(model.stable_dt_s) + " s");
      dt = scene.time().fixed_dt_s();
    }
    std::uint64_t coupled_from_step = 0;
    double coupled_from_wall = 0.0;
    State3d s = make_state3d(model, revolve_positions(model.mesh, axi.nodes, axi.twist_rad), t.rim().mass_kg(),
                             t.rim().spin_inertia_kg_m2());
    s.dt_s = dt;
    s.pressure_Pa = t.inflation_pressure_pa();
    // Forces of the ground on the tyre: the rigid road, or a terrain solver's loads.
    auto ground_fx = [&] { return s.road.force_x_N + s.terrain.loads.total_x_N; };
    auto ground_fy = [&] { return s.road.force_y_N + s.terrain.loads.total_y_N; };
    auto ground_fz = [&] { return s.road.force_z_N + s.terrain.loads.total_z_N; };
    auto ground_area = [&] { return s.road.contact_area_m2 + s.terrain.loads.contact_area_m2; };
    const auto& st = t.stages();
    const double total_time = st.transfer_check_s() + st.loading_s() + st.rolling_s();
    cosim::Progress progress(scene.name(), total_time, options.quiet);
    progress_ptr = &progress;
    csv = std::make_unique<cosim::CsvWriter>(
        out + "/tyre.csv",
        std::vector<std::string>{"time_s", "stage", "rim_x_m", "rim_z_m", "rim_angle_rad", "rim_vx_m_per_s",
                                 "rim_vz_m_per_s", "rim_omega_rad_per_s", "rim_vertical_force_N", "rm2_Nm",
                                 "road_force_x_N", "road_force_y_N", "road_force_z_N", "contact_area_m2",
                                 "kinetic_J", "internal_J", "hourglass_J", "external_work_J",
                                 "energy_balance_error"});
    const double csv_interval = scene.output().csv_interval_s();
    double next_csv = 0.0;
    const std::uint64_t max_steps = scene.time().max_steps();
    FrameWriter frames(out, options.write_vtk ? scene.output().vtk_interval_s() : 0.0);
    // Runs a stage for `duration`; `each_step` may end it early by returning true.
    auto run_stage = [&](int stage, double duration, const std::function<RimDrive(double)>& drive_at,
                         const std::function<bool()>& each_step) {
      const double t_end = s.time_s + duration;
      const double t0 = s.time_s;
      while (s.time_s < t_end - 0.5 * s.dt_s) {
        if (cosim::interrupt_requested())
          throw cosim::Error("interrupted by a signal at step " + std::to_string(s.step));
        if (max_steps > 0 && s.step >= max_steps) return;
        if (!step3d(model, s, drive_at(s.time_s - t0)))
          throw cosim::Error("non-finite state at t = " + cosim::number_text(s.time_s) + " s (step " +
                             std::to_string(s.step) + ")");
        steps = s.step, sim_time = s.time_s;
        const bool done = each_step && each_step();
        if (s.time_s >= next_csv || done) {
          csv->row({s.time_s, double(stage), s.rim.x, s.rim.z, s.rim.angle, s.rim.vx, s.rim.vz, s.rim.omega,
                    s.rim.tyre_force_z_N, s.rim.rm2_Nm, ground_fx(), ground_fy(), ground_fz(),
                    ground_area(), s.energy.kinetic_J, s.energy.internal_J, s.energy.hourglass_J,
                    s.energy.external_work_J, s.energy.balance_error()});
          next_csv = s.time_s + csv_interval;
        }
        frames.maybe_write(model, s);
        progress.update(s.time_s, s.step);
        if (done) return;
      }
    };

    // 3. Check at rest after the transfer: no damping, rim held.
    double max_kinetic = 0.0;
    run_stage(0, st.transfer_check_s(), [](double) { RimDrive d; d.hold_z = true; return d; },
              [&] {
                max_kinetic = std::max(max_kinetic, s.energy.kinetic_J);
                return false;
              });
    results["radial_growth_3d_m"] = mean_radius_of(model.mesh, s, centre) - r0;
    results["kinetic_energy_after_transfer_J"] = s.energy.kinetic_J;
    results["max_kinetic_energy_after_transfer_J"] = max_kinetic;
    results["internal_energy_after_transfer_J"] = s.energy.internal_J;
    const double growth_axi = results["axisym_radial_growth_m"].get<double>();
    results["radial_growth_difference_percent"] =
        growth_axi != 0.0 ? 100.0 * (results["radial_growth_3d_m"].get<double>() - growth_axi) / growth_axi : 0.0;

    // 4. Loading onto the road or the terrain (dynamic relaxation).
    if (options.terrain) {
      // The terrain's undisturbed surface is z = 0 (docs/coupling.md): lift the
      // tyre so that its lowest point is initial_gap above it, then join the run.
      const auto& c = scene.coupling();
      const double gap = c.initial_gap_m() > 0 ? c.initial_gap_m() : 0.005;
      double lowest = 1e30;
      for (int n : model.contact_nodes) lowest = std::min(lowest, s.z[n]);
      const double lift = gap - lowest;
      for (double& z : s.z) z += lift;
      s.rim.z += lift;
      s.road.height_m = 0.0;  // heights below are measured from the terrain surface
      s.terrain.port = options.terrain;
      s.terrain.surface = make_contact_surface(model);
      if (!options.quiet)
        std::fprintf(stderr, "[%s] joining the terrain and the coupler (%zu surface facets)\n", scene.name().c_str(),
                     s.terrain.surface.facet_count());
      // The coupler answers with the coupling window; the tyre fills it with
      // equal sub-steps no larger than its own stable step (one in the common-step scheme).
      const double window = options.terrain->connect(s.terrain.surface, s.dt_s);
      s.terrain.substeps = cosim::substeps_per_window(window, s.dt_s);
      s.dt_s = s.terrain.substeps == 1 ? window : window / s.terrain.substeps;
      s.time_stages = true;  // the exchange's share of the wall time (summary "performance")
      coupled_from_step = s.step;
      coupled_from_wall = wall();
      summary["coupled_dt_s"] = s.dt_s;
      summary["coupling_window_s"] = window;
      summary["tyre_substeps"] = s.terrain.substeps;
      results["coupled_time_step_s"] = s.dt_s;
    }
    if (st.loading_s() > 0) {
      if (!options.terrain)
        place_road(model, s, t.road().initial_gap_m(), t.road().friction_coefficient(), t.road().penalty_scale());
      const double radius0 = free_radius(model, s);
      s.damping_per_s = st.loading_damping_per_s();
      const double load = t.rim().wheel_load_n(), ramp = t.rim().load_ramp_time_s();
      const double loading_start = s.time_s;
      double previous_kinetic = 0.0;
      bool at_rest = false;
      run_stage(1, st.loading_s(), [&](double tau) {
        RimDrive d;
        d.wheel_load_N = load * smooth_ramp(tau, ramp);
        return d;
      }, [&] {
        if (st.loading_kinetic_damping()) {
          if (s.energy.kinetic_J < previous_kinetic) {
            zero_velocities(s);
            previous_kinetic = 0.0;
          } else {
            previous_kinetic = s.energy.kinetic_J;
          }
        }
        const double tol = st.loading_rest_tolerance();
        if (tol <= 0.0 || s.time_s - loading_start < ramp) return false;
        at_rest = std::fabs(ground_fz() - load) < tol * load &&
                  std::fabs(s.rim.tyre_force_z_N - load) < tol * load &&
                  s.energy.kinetic_J < tol * s.energy.internal_J;
        return at_rest;
      });
      results["loading_time_s"] = s.time_s - loading_start;
      results["loading_came_to_rest"] = at_rest;
      const double loaded_radius = s.rim.z - s.road.height_m;
      results["unloaded_radius_m"] = radius0;
      results["loaded_radius_m"] = loaded_radius;
      results["vertical_deflection_m"] = radius0 - loaded_radius;
      results["contact_area_m2"] = ground_area();
      results["rim_vertical_force_N"] = s.rim.tyre_force_z_N;  // the tyre holding the rim up
      results["road_vertical_force_N"] = ground_fz();
      results["wheel_load_N"] = load;
      // Depth of the lowest tyre point below the undisturbed terrain surface z = 0.
      if (options.terrain) results["sinkage_m"] = free_radius(model, s) - s.rim.z;
      results["kinetic_energy_after_loading_J"] = s.energy.kinetic_J;
      // On a terrain solver the footprint is the coupler's (contact_pressure.png).
      if (!options.terrain) write_footprint(out, model, s);
      s.damping_per_s = 0.0;
    }

    // 5. Rolling.
    if (st.rolling_s() > 0) {
      const auto& rim = t.rim();
      const double window = st.average_last_s() > 0 ? st.average_last_s() : 0.5 * st.rolling_s();
      const double t_start = s.time_s, t_window = t_start + st.rolling_s() - window;
      // Effective rolling radius estimate R - deflection / 3 (a common estimate; Pacejka, Tire and Vehicle Dynamics, 2006).
      const double unloaded = results.value("unloaded_radius_m", free_radius(model, s));
      const double spin_up_radius = unloaded - (unloaded - (s.rim.z - s.road.height_m)) / 3.0;
      double x_w = 0, a_w = 0, fx_sum = 0, m_sum = 0, fz_sum = 0, h_sum = 0, w_sum = 0;
      long n_w = 0;
      bool in_window = false;
      run_stage(2, st.rolling_s(), [&](double tau) {
        RimDrive d;
        d.hold_x = false;
        d.forward_speed_m_per_s = rim.forward_speed_m_per_s() * smooth_ramp(tau, rim.speed_ramp_time_s());
        d.wheel_load_N = rim.wheel_load_n();
        if (rim.spin_case() == sc::RimSpec::kAngularVelocityRadPerS) {
          d.angular_velocity_rad_per_s = rim.angular_velocity_rad_per_s() * smooth_ramp(tau, rim.speed_ramp_time_s());
        } else if (tau < rim.speed_ramp_time_s()) {
          // Spin-up: while the speed ramps the spin follows it at the estimated free
          // rolling radius, so that the tyre starts rolling instead of sliding; then the
          // spin is released (free rolling) and the torque ramps in.
          d.angular_velocity_rad_per_s = d.forward_speed_m_per_s / spin_up_radius;
        } else {
          d.spin_prescribed = false;
          d.drive_torque_Nm = rim.drive_torque_nm() * smooth_ramp(tau - rim.speed_ramp_time_s(), rim.torque_ramp_time_s());
        }
        return d;
      }, [&] {
        if (s.time_s < t_window) return false;
        if (!in_window) x_w = s.rim.x, a_w = s.rim.angle, in_window = true;
        fx_sum += ground_fx(), m_sum += s.rim.rm2_Nm, fz_sum += ground_fz(), ++n_w;
        h_sum += s.rim.z - s.road.height_m, w_sum += s.rim.omega;
        return false;
      });
      const double turned = s.rim.angle - a_w;
      results["rolling_distance_m"] = s.rim.x;
      results["rolling_revolutions"] = s.rim.angle / (2.0 * M_PI);
      results["rolling_radius_m"] = std::fabs(turned) > 1e-9 ? (s.rim.x - x_w) / turned : 0.0;
      results["rm2_Nm"] = n_w ? m_sum / n_w : 0.0;
      results["road_longitudinal_force_N"] = n_w ? fx_sum / n_w : 0.0;
      results["road_vertical_force_rolling_N"] = n_w ? fz_sum / n_w : 0.0;
      // Window means: the rim height above the road is the lever arm of the road's
      // longitudinal force about the axle (moment balance of the tyre at steady state).
      results["loaded_radius_rolling_m"] = n_w ? h_sum / n_w : s.rim.z - s.road.height_m;
      results["spin_rate_rad_per_s"] = n_w ? w_sum / n_w : s.rim.omega;
      results["road_longitudinal_force_moment_Nm"] =
          n_w ? fx_sum / n_w * results["loaded_radius_rolling_m"].get<double>() : 0.0;
      results["energy_balance_error"] = s.energy.balance_error();
      results["energy_balance_J"] = s.energy.balance_J();
      results["drive_torque_Nm"] = rim.spin_case() == sc::RimSpec::kDriveTorqueNm ? rim.drive_torque_nm() : 0.0;
      results["averaging_window_s"] = window;
    }
    frames.write(model, s);
    progress.finish(s.time_s, s.step);
    summary["energy"] = energy_json(s.energy);
    summary["dt_s"] = s.dt_s;
    // Whole-run figures (inflation and set-up included); bench/tyre_bench times the step alone.
    const double per_element_step = s.step ? wall() / (double(s.step) * model.mesh.hexes.size()) : 0.0;
    summary["performance"] = {{"steps_per_s", wall() > 0 ? s.step / wall() : 0.0},
                              {"us_per_element_step", 1e6 * per_element_step},
                              {"core_us_per_element_step", 1e6 * per_element_step * cosim::max_threads()}};
    if (options.terrain) {
      const auto& st = s.stage_times;
      const double coupled_steps = double(s.step - coupled_from_step);
      const double compute = st.internal_forces_s + st.contact_s + st.rest_s;
      summary["performance"]["coupled_steps"] = s.step - coupled_from_step;
      summary["performance"]["coupling_windows"] = s.terrain.exchange;
      summary["performance"]["coupling_window_s"] = summary["coupling_window_s"];
      summary["performance"]["tyre_substeps"] = s.terrain.substeps;
      // What the terrain's loads gave the tyre over the run (the terrain books the same).
      const double* impulse = s.terrain.impulse_Ns;
      results["terrain_impulse_Ns"] = {impulse[0], impulse[1], impulse[2]};
      summary["performance"]["coupled_wall_s"] = wall() - coupled_from_wall;
      summary["performance"]["exchange_wait_s"] = st.exchange_s;
      summary["performance"]["compute_s"] = compute;
      // Where the tyre's time goes (stage wall times summed over the coupled steps).
      summary["performance"]["stages_s"] = {{"element_forces_and_gather", st.internal_forces_s},
                                            {"road_contact", st.contact_s},
                                            {"pressure_damping_rim_update_energy", st.rest_s}};
      summary["performance"]["compute_s_per_step"] = coupled_steps > 0 ? compute / coupled_steps : 0.0;
    }
    csv.reset();
    if (options.terrain) options.terrain->finish(false, "");
    write_plots(out);
    write_summary(max_steps > 0 && s.step >= max_steps ? "stopped_at_max_steps" : "completed");
    return summary;
  } catch (const std::exception& e) {
    if (csv) csv->flush();
    if (options.terrain) {
      try {
        options.terrain->finish(true, e.what());
      } catch (const std::exception&) {
        // The peers learn of the failure by their time-out instead.
      }
    }
    summary["error"] = e.what();
    write_summary("failed");
    throw cosim::Error(e.what());
  }
}

}  // namespace tyre_fe
