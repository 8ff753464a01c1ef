#include "hub.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "coupler/facet_geometry.hpp"
#include "cosim/coupling_window.hpp"
#include "coupler/forces.hpp"
#include "coupler/friction.hpp"
#include "coupler/wire.hpp"
#include "cosim/interrupt.hpp"
#include "cosim/outputs.hpp"
#include "cosim/progress.hpp"

namespace coupler {
namespace {

using Clock = std::chrono::steady_clock;
namespace sc = cosim::scene;

// The terrain the tyre meets, from its material (the scene's blocks, filled by coupling.terrain).
TerrainKind terrain_kind(const sc::Scene& scene) {
  bool hard = false;
  for (const auto& b : scene.sph().blocks()) {
    if (b.material().has_water()) return TerrainKind::water;
    hard = hard || b.material().snow().snow_class() == sc::HARD_SNOW;
  }
  return hard ? TerrainKind::snow_hard : TerrainKind::snow_soft;
}

FrictionRules friction_rules(const cosim::LoadedScene& loaded) {
  const auto& c = loaded.message.coupling();
  FrictionRules rules;
  if (c.base_friction_coefficient() > 0) rules.base_mu = c.base_friction_coefficient();
  if (c.sipe_equivalent_friction_coefficient() > 0) rules.sipe_equivalent_mu = c.sipe_equivalent_friction_coefficient();
  for (int i = 0; i < c.tag_friction_size(); ++i) {
    try {
      add_tag_override(rules, c.tag_friction(i).tag(), c.tag_friction(i).friction_coefficient());
    } catch (const cosim::Error& e) {
      throw cosim::Error(loaded.locator().child("coupling").where("tag_friction") + ": " + e.what());
    }
  }
  validate(rules);
  return rules;
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

nlohmann::json run_hub(Session& session, const cosim::LoadedScene& loaded, const HubOptions& options) {
  const sc::Scene& scene = loaded.message;
  const auto& c = scene.coupling();
  cosim::make_folder(options.out_dir);
  const std::string out = options.out_dir;
  nlohmann::json summary = {{"scene", scene.name()}, {"scene_file", loaded.file},
                            {"revision", cosim::source_revision()}, {"participant", "coupler"},
                            {"status", "running"}};
  nlohmann::json results = nlohmann::json::object();
  std::unique_ptr<cosim::CsvWriter> csv;
  std::uint64_t step = 0;
  double sim_time = 0.0;
  const auto start = Clock::now();
  auto write_summary = [&](const std::string& status) {
    summary["status"] = status;
    summary["results"] = results;
    summary["wall_time_s"] = seconds_since(start);
    summary["sim_time_s"] = sim_time;
    summary["steps"] = step;
    summary["rejected_samples"] = {{"other_run", session.rejected_run_id()}, {"wrong_step", session.rejected_step()}};
    cosim::write_json(out + "/summary.json", summary);
  };
  try {
    const FrictionRules rules = friction_rules(loaded);
    const TerrainKind terrain = terrain_kind(scene);
    const bool sipes = scene.tyre().tread().variant() == sc::BLOCK_SIPES;
    auto& p = session.participant();
    auto mesh_in = p.create_reader<tp::SurfaceMesh>();
    auto tyre_kinematics_in = p.create_reader<tp::SurfaceKinematics>(channel_qos<tp::SurfaceKinematics>(kTyreChannel));
    auto wheel_in = p.create_reader<tp::WheelState>();
    auto terrain_kinematics_out = p.create_writer<tp::SurfaceKinematics>(channel_qos<tp::SurfaceKinematics>(kTerrainChannel));
    auto terrain_loads_in = p.create_reader<tp::ContactLoads>(channel_qos<tp::ContactLoads>(kTerrainChannel));
    auto tyre_loads_out = p.create_writer<tp::ContactLoads>(channel_qos<tp::ContactLoads>(kTyreChannel));
    auto summary_out = p.create_writer<tp::ForceSummary>();
    if (!options.quiet) std::fprintf(stderr, "[coupler] waiting for the tyre and the terrain (run %016llx)\n",
                                     static_cast<unsigned long long>(session.run_id()));
    const tp::HandshakeResult joined = session.join(
        {tp::Role::tyre, tp::Role::terrain}, 0.0,
        {mesh_in.get(), tyre_kinematics_in.get(), wheel_in.get(), terrain_kinematics_out.get(),
         terrain_loads_in.get(), tyre_loads_out.get()});
    // The coupling window (docs/coupling.md): the terrain's stable step, the
    // tyre sub-cycling inside it (multi-rate), or the smaller of the two steps
    // for both (the common-step reference).
    const double tyre_dt = joined.peer_time_step_s[0], terrain_dt = joined.peer_time_step_s[1];
    if (!(tyre_dt > 0) || !(terrain_dt > 0))
      throw cosim::Error("the tyre (" + cosim::number_text(tyre_dt) + " s) and the terrain (" +
                         cosim::number_text(terrain_dt) + " s) must both propose a stable step");
    const bool common_step = c.scheme() == sc::COMMON_STEP;
    const double dt = common_step ? std::min(tyre_dt, terrain_dt) : terrain_dt;
    const int substeps = cosim::substeps_per_window(dt, tyre_dt);
    session.announce_start(dt, common_step ? "common step: the smaller stable step"
                                           : "multi-rate: the terrain's step, the tyre sub-cycles");
    summary["time_step"] = {{"agreed_dt_s", dt}, {"coupling_window_s", dt}, {"tyre_substeps", substeps},
                            {"tyre_proposed_dt_s", tyre_dt}, {"terrain_proposed_dt_s", terrain_dt},
                            {"scheme", common_step ? "common step: one step for both, every step exchanged"
                                                   : "multi-rate: one exchange per terrain step, the tyre sub-cycles "
                                                     "with the terrain's loads held"}};
    summary["friction"] = {{"terrain", terrain_kind_name(terrain)}, {"tread_has_sipes", sipes},
                           {"base", rules.base_mu}, {"sipe_equivalent_on_tread_top", rules.sipe_equivalent_mu}};
    if (!options.quiet)
      std::fprintf(stderr, "[coupler] started: window %.4g s, %d tyre sub-steps (tyre %.4g s, terrain %.4g s)\n", dt,
                   substeps, tyre_dt, terrain_dt);

    tp::SampleFilter mesh_filter(session.run_id()), tyre_filter(session.run_id()), wheel_filter(session.run_id()),
        terrain_filter(session.run_id());
    tp::SurfaceMesh mesh;
    if (!session.wait_step(*mesh_in, mesh_filter, 0, mesh, "SurfaceMesh", tp::Role::tyre)) throw cosim::Error("stopped before the first step");
    std::vector<FacetTag> tags(mesh.facet_tags.begin(), mesh.facet_tags.end());
    std::vector<double> mu_all;
    fill_facet_friction(tags, sipes, terrain, rules, mu_all);
    std::vector<double> x = mesh.x_m, y = mesh.y_m, z = mesh.z_m;
    const double rolling_radius = c.rolling_radius_m() > 0 ? c.rolling_radius_m() : 0.36;
    results["rolling_radius_for_F5_m"] = rolling_radius;

    csv = std::make_unique<cosim::CsvWriter>(
        out + "/forces.csv",
        std::vector<std::string>{"time_s", "step", "traction_force_N", "motion_resistance_N", "groove_force_N",
                                 "vertical_pressure_force_N", "rolling_resistance_moment_Nm",
                                 "rolling_resistance_force_N", "drawbar_pull_N", "net_longitudinal_pressure_force_N",
                                 "traction_minus_rrf_N", "sinkage_m", "contact_area_m2", "rim_x_m", "rim_z_m",
                                 "spin_rate_rad_per_s", "applied_torque_Nm", "rm2_Nm", "contact_force_x_N",
                                 "contact_force_z_N"});
    struct Row { double t; ForceDecomposition d; };
    std::vector<Row> rows;
    const double planned = scene.tyre().stages().loading_s() + scene.tyre().stages().rolling_s();
    cosim::Progress progress("coupler", planned, options.quiet);
    tp::SurfaceKinematics k;
    tp::WheelState wheel;
    tp::ContactLoads loads;
    double exchange_s = 0.0, nodes_sent = 0.0, facets_sent = 0.0, loaded_nodes = 0.0;
    DecompositionOptions decomposition;
    FacetLoads last_facets;
    for (step = 0;; ++step) {
      if (cosim::interrupt_requested()) throw cosim::Error("interrupted by a signal at step " + std::to_string(step));
      if (!session.wait_step(*tyre_kinematics_in, tyre_filter, step, k, "SurfaceKinematics", tp::Role::tyre)) break;
      const auto t0 = Clock::now();
      // Friction per listed facet: the coupler's decision (thesis 4.3, 4.4, 6.1).
      // Sipe walls are not handed on: a sipe is a slit (0.6 mm) that no particle
      // enters, and its effect on the snow is the tread top's equivalent
      // coefficient (thesis 4.4, 6.1); particles would otherwise be caught
      // between its two coincident walls.
      std::size_t kept = 0;
      k.friction_coefficient.resize(k.facets.size());
      for (std::size_t i = 0; i < k.facets.size(); ++i) {
        const auto f = k.facets[i];
        if (f >= mu_all.size())
          throw cosim::Error("SurfaceKinematics of step " + std::to_string(step) + ": facet " + std::to_string(f) +
                             " is not in the surface mesh");
        if (tags[f] == FacetTag::sipe_wall) continue;
        k.facets[kept] = f, k.friction_coefficient[kept] = mu_all[f], ++kept;
      }
      k.facets.resize(kept), k.friction_coefficient.resize(kept);
      terrain_kinematics_out->write(k);
      exchange_s += seconds_since(t0);
      nodes_sent += k.nodes.size(), facets_sent += k.facets.size();
      if (!session.wait_step(*wheel_in, wheel_filter, step, wheel, "WheelState", tp::Role::tyre)) break;
      if (!session.wait_step(*terrain_loads_in, terrain_filter, step, loads, "ContactLoads", tp::Role::terrain)) break;
      const auto t1 = Clock::now();
      tyre_loads_out->write(loads);
      exchange_s += seconds_since(t1);
      loaded_nodes += loads.nodes.size();
      sim_time = k.header.sim_time_s;
      // The decomposition, from the current facet geometry.
      for (std::size_t j = 0; j < k.nodes.size(); ++j) {
        const auto n = k.nodes[j];
        x[n] = k.x_m[j], y[n] = k.y_m[j], z[n] = k.z_m[j];
      }
      const FacetGeometry geometry = quad_facet_geometry(x, y, z, mesh.facet_nodes);
      const FacetLoads facet_loads = facet_loads_from_contact(loads, tags, geometry);
      const ForceDecomposition d = decompose_forces(facet_loads, wheel_input(wheel, rolling_radius), decomposition);
      summary_out->write(force_summary(d, k.header));
      double fx = 0.0, fz = 0.0;
      for (std::size_t j = 0; j < loads.nodes.size(); ++j) fx += loads.fx_N[j], fz += loads.fz_N[j];
      csv->row({sim_time, double(step), d.traction_force_N, d.motion_resistance_N, d.groove_force_N,
                d.vertical_pressure_force_N, d.rolling_resistance_moment_Nm, d.rolling_resistance_force_N,
                d.drawbar_pull_N, d.net_longitudinal_pressure_force_N, d.traction_minus_rrf_N, d.sinkage_m,
                d.contact_area_m2, wheel.rim_x_m, wheel.rim_z_m, wheel.spin_rate_radps, wheel.applied_torque_Nm,
                wheel.reaction_moment_y_Nm, fx, fz});
      rows.push_back({sim_time, d});
      last_facets = facet_loads;
      progress.update(sim_time, step + 1);
    }
    progress.finish(sim_time, step);
    csv->flush();
    // Steady means over the last average_last_s of the run (thesis 6.1: results
    // "taken at the steady state region").
    const double window = c.average_last_s() > 0 ? c.average_last_s() : scene.tyre().stages().average_last_s();
    const double from = rows.empty() ? 0.0 : rows.back().t - window;
    ForceDecomposition mean;
    long n = 0;
    for (const auto& r : rows) {
      if (window > 0 && r.t < from) continue;
      const auto& d = r.d;
      mean.traction_force_N += d.traction_force_N, mean.motion_resistance_N += d.motion_resistance_N;
      mean.groove_force_N += d.groove_force_N, mean.rolling_resistance_force_N += d.rolling_resistance_force_N;
      mean.drawbar_pull_N += d.drawbar_pull_N;
      mean.net_longitudinal_pressure_force_N += d.net_longitudinal_pressure_force_N;
      mean.traction_minus_rrf_N += d.traction_minus_rrf_N, mean.sinkage_m += d.sinkage_m;
      mean.contact_area_m2 += d.contact_area_m2, mean.vertical_pressure_force_N += d.vertical_pressure_force_N;
      ++n;
    }
    auto avg = [&](double v) { return n ? v / n : 0.0; };
    results["averaging_window_s"] = window;
    results["averaged_steps"] = n;
    results["traction_force_N"] = avg(mean.traction_force_N);
    results["motion_resistance_N"] = avg(mean.motion_resistance_N);
    results["groove_force_N"] = avg(mean.groove_force_N);
    results["rolling_resistance_force_N"] = avg(mean.rolling_resistance_force_N);
    results["drawbar_pull_N"] = avg(mean.drawbar_pull_N);
    results["net_longitudinal_pressure_force_N"] = avg(mean.net_longitudinal_pressure_force_N);
    results["traction_minus_rrf_N"] = avg(mean.traction_minus_rrf_N);
    results["vertical_pressure_force_N"] = avg(mean.vertical_pressure_force_N);
    results["sinkage_m"] = avg(mean.sinkage_m);
    results["contact_area_m2"] = avg(mean.contact_area_m2);
    if (!rows.empty()) {
      results["final_contact_area_m2"] = rows.back().d.contact_area_m2;
      results["final_sinkage_m"] = rows.back().d.sinkage_m;
    }
    for (const auto* f : {&mesh_filter, &tyre_filter, &wheel_filter, &terrain_filter}) session.count_rejections(*f);
    const double wall = seconds_since(start);
    summary["performance"] = {{"coupler_forwarding_s", exchange_s}, {"steps_per_s", wall > 0 ? step / wall : 0.0},
                              {"windows_per_s", wall > 0 ? step / wall : 0.0},
                              {"coupling_window_s", dt}, {"tyre_substeps", substeps}};
    summary["payload"] = {{"mean_surface_nodes_per_step", step ? nodes_sent / step : 0.0},
                          {"mean_surface_facets_per_step", step ? facets_sent / step : 0.0},
                          {"mean_loaded_nodes_per_step", step ? loaded_nodes / step : 0.0}};
    csv.reset();
    // Contact pressure of the last step, per contacted facet (a picture and its numbers).
    {
      cosim::CsvWriter map(out + "/contact_pressure.csv",
                           {"centroid_x_m", "centroid_y_m", "centroid_z_m", "contact_pressure_Pa", "contact_area_m2"});
      for (std::size_t i = 0; i < last_facets.size(); ++i) {
        const double a = last_facets.contact_area_m2[i];
        const double pn = std::sqrt(last_facets.pressure_x_N[i] * last_facets.pressure_x_N[i] +
                                    last_facets.pressure_y_N[i] * last_facets.pressure_y_N[i] +
                                    last_facets.pressure_z_N[i] * last_facets.pressure_z_N[i]);
        map.row({last_facets.centroid_x_m[i], last_facets.centroid_y_m[i], last_facets.centroid_z_m[i],
                 a > 0 ? pn / a : 0.0, a});
      }
    }
    cosim::plot_csv_map(out + "/contact_pressure.csv", out + "/contact_pressure.png", 1, 2, 4,
                        scene.name() + ": contact pressure on the tyre (last step, seen from above)", "x [m]", "y [m]",
                        "pressure [Pa]");
    if (!rows.empty()) {
      cosim::plot_csv(out + "/forces.csv", out + "/forces.png", 1,
                      {{3, "traction F3"}, {4, "motion resistance F1"}, {5, "groove F2"}, {8, "F5"}, {9, "drawbar pull"}},
                      scene.name() + ": force decomposition", "time [s]", "force [N]");
    }
    write_summary("completed");
    return summary;
  } catch (const std::exception& e) {
    if (csv) csv->flush();
    try {
      session.send_failure(step, std::string("coupler: ") + e.what());
    } catch (const std::exception&) {
    }
    summary["error"] = e.what();
    write_summary("failed");
    throw cosim::Error(e.what());
  }
}

}  // namespace coupler
