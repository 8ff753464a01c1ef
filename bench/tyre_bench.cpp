// Speed of the explicit 3D tyre step: microseconds per element-step on 1 and 2
// threads and the share of internal forces, contact and the rest.
//   tyre_bench [--scene FILE] [--steps N] [--set field=value ...]
// The tyre is inflated (axisymmetric), revolved, placed on the road with its
// wheel load and stepped N times from the same state on each thread count.
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <omp.h>

#include "cosim/error.hpp"
#include "cosim/scene_io.hpp"
#include "tyre_fe/model3d.hpp"
#include "tyre_fe/scene.hpp"
#include "tyre_fe/solver3d.hpp"

int main(int argc, char** argv) {
  CLI::App app{"tyre_bench: explicit 3D tyre step timing"};
  std::string scene_file = "configs/scenes/tyre_footprint.textproto";
  std::vector<std::string> sets;
  int steps = 200;
  app.add_option("--scene", scene_file, "tyre scene");
  app.add_option("--steps", steps, "steps per thread count");
  app.add_option("--set", sets, "override a scene field");
  CLI11_PARSE(app, argc, argv);
  try {
    using namespace tyre_fe;
    const auto scene = cosim::load_scene(scene_file, sets);
    cosim::ValidationReport report;
    validate_tyre_scene(*scene, report);
    report.throw_if_failed();
    const auto& t = scene->message.tyre();
    const TyreSetup setup = tyre_setup(*scene);
    const CrossSection section = make_section(setup);
    AxisymLoadCase inflation;
    inflation.pressure_Pa = t.inflation_pressure_pa();
    inflation.fixed_nodes = section.rim_nodes;
    const AxisymResult axi = solve_axisym(section, setup.materials, inflation);
    Model3dOptions options;
    options.mass_scaling_target_dt_s = t.mass_scaling_target_dt_s();
    const Model3d model = build_model3d(revolve(section, setup.pattern), setup.materials, section, options);
    const auto x = revolve_positions(model.mesh, axi.nodes, axi.twist_rad);
    State3d start = make_state3d(model, x, t.rim().mass_kg(), t.rim().spin_inertia_kg_m2());
    start.pressure_Pa = t.inflation_pressure_pa();
    place_road(model, start, -0.01, 0.3, 0.1);  // 10 mm into the road: contact is active
    start.time_stages = true;
    RimDrive drive;
    drive.wheel_load_N = t.rim().wheel_load_n();
    const std::size_t ne = model.mesh.hexes.size();
    std::printf("tyre_bench: %s, %zu hexahedra, %zu nodes, %zu contact candidates, dt %.3g s, %d steps\n",
                scene_file.c_str(), ne, model.mesh.nodes.size(), model.contact_nodes.size(), model.stable_dt_s, steps);
    if (options.mass_scaling_target_dt_s > 0.0)
      std::printf("mass scaling to %.3g s (unscaled %.3g s): %.3f kg added, %.2f %% of the tyre's %.2f kg\n",
                  options.mass_scaling_target_dt_s, model.unscaled_dt_s, model.added_mass_kg,
                  100.0 * model.added_mass_kg / model.physical_mass_kg, model.physical_mass_kg);
    std::printf("%8s %12s %14s %22s %10s %10s %8s\n", "threads", "wall_s", "us/elem-step", "core-us/elem-step",
                "internal%", "contact%", "rest%");
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      State3d s = start;
      for (int k = 0; k < 5; ++k) step3d(model, s, drive);  // warm-up
      s.stage_times = {};
      const double t0 = omp_get_wtime();
      for (int k = 0; k < steps; ++k) step3d(model, s, drive);
      const double wall = omp_get_wtime() - t0;
      const double us = 1e6 * wall / (double(steps) * ne);
      const auto& st = s.stage_times;
      const double sum = st.internal_forces_s + st.contact_s + st.rest_s;
      std::printf("%8d %12.3f %14.4f %22.4f %10.1f %10.1f %8.1f\n", threads, wall, us, us * threads,
                  100 * st.internal_forces_s / sum, 100 * st.contact_s / sum, 100 * st.rest_s / sum);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tyre_bench: error: %s\n", e.what());
    return 2;
  }
}
