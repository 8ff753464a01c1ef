// plate_sinkage_fe: the plate-sinkage scene on a Lagrangian axisymmetric mesh of
// the same snow (snow_fe/plate_fe.hpp), the independent check of the snow's
// parameters beside the SPH run.
//   plate_sinkage_fe SCENE --out DIR [--set field.path=value ...] [--element-size M] [--quiet]
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "cosim/error.hpp"
#include "cosim/interrupt.hpp"
#include "cosim/result_references.hpp"
#include "snow_fe/plate_fe.hpp"
#include "snow_sph/scene.hpp"

int main(int argc, char** argv) {
  CLI::App app{"plate_sinkage_fe: the plate-sinkage test on a Lagrangian axisymmetric mesh of the scene's snow"};
  std::string scene_file, out_dir = "out";
  std::vector<std::string> sets;
  double element_size = 0.0;
  bool quiet = false;
  app.add_option("scene", scene_file, "plate-sinkage scene file (.textproto)")->required();
  app.add_option("--out", out_dir, "output folder");
  app.add_option("--set", sets, "override a scene field: field.path=value");
  app.add_option("--element-size", element_size, "element size [m] (default: the scene's particle spacing)");
  app.add_flag("--quiet", quiet, "no progress line");
  CLI11_PARSE(app, argc, argv);
  cosim::install_interrupt_handler();
  try {
    const auto scene = snow_sph::load_sph_scene(scene_file, sets);
    const auto setup = snow_fe::plate_fe_setup_from_scene(*scene, element_size);
    const auto summary = snow_fe::run_plate_fe(setup, out_dir, quiet);
    const auto& r = summary["results"];
    std::printf("%s: %s after %.3f s simulated, %.1f s wall\n", setup.name.c_str(),
                summary["status"].get<std::string>().c_str(), summary["simulated_time_s"].get<double>(),
                summary["wall_time_s"].get<double>());
    if (setup.prescribed_speed_m_per_s > 0.0)
      std::printf("largest snow force on the plate %.0f N at %.3f m (load of the laboratory test 1867 N)\n",
                  r["largest_snow_force_N"].get<double>(), r["depth_at_largest_snow_force_m"].get<double>());
    else
      std::printf("plate displacement %.3f m, plate speed %.4f m/s\n",
                  r["plate_displacement_m"].get<double>(), r["plate_velocity_z_m_per_s"].get<double>());
    std::printf("%s", cosim::reference_lines(summary.value("comparison", nlohmann::json())).c_str());
    if (summary["status"] == "mesh_inverted")
      std::printf("the mesh inverted under the plate's edge: a Lagrangian mesh's limit, not a failure of the run; "
                  "the results above are those of its last step\n");
    return summary["status"] == "failed" ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "plate_sinkage_fe: %s\n", e.what());
    return 2;
  }
}
