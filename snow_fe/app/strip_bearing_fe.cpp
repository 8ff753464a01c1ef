// strip_bearing_fe: the strip-footing scene (configs/scenes/strip_bearing.textproto)
// on a Lagrangian plane-strain mesh of the same snow (snow_fe/strip_fe.hpp), the
// finite-element side of the thin-layer bearing check.
//   strip_bearing_fe SCENE --out FILE.csv [--set field.path=value ...] [--base rough|smooth]
//                    [--elements-per-width N]
#include <cstdio>
#include <exception>
#include <fstream>

#include <CLI/CLI.hpp>

#include "snow_fe/strip_fe.hpp"
#include "snow_sph/scene.hpp"

int main(int argc, char** argv) {
  CLI::App app{"strip_bearing_fe: a rigid strip into a layer on a rigid base, plane-strain FE of the scene's snow"};
  std::string scene_file, out_file = "strip_fe.csv", base = "smooth";
  std::vector<std::string> sets;
  double elements_per_width = 20.0;
  bool free_end = false;
  app.add_option("scene", scene_file, "strip scene file (.textproto)")->required();
  app.add_option("--out", out_file, "CSV of the footing's displacement and pressure");
  app.add_option("--set", sets, "override a scene field: field.path=value");
  app.add_option("--base", base, "the layer's base: rough (fixed) or smooth (a roller)")
      ->check(CLI::IsMember({"rough", "smooth"}));
  app.add_flag("--free-end", free_end, "the layer's far end free instead of a roller (a layer that may spread)");
  app.add_option("--elements-per-width", elements_per_width, "elements across the footing's width B");
  CLI11_PARSE(app, argc, argv);
  try {
    const auto scene = snow_sph::load_sph_scene(scene_file, sets);
    auto setup = snow_fe::strip_setup_from_scene(*scene, base == "rough", 0.0);
    setup.element_size_m = setup.footing_width_m / elements_per_width;
    setup.confined_end = !free_end;
    const auto r = snow_fe::run_strip_bearing(setup, 100);
    std::ofstream csv(out_file);
    csv << "displacement_m,pressure_Pa\n";
    for (std::size_t k = 0; k < r.pressure_Pa.size(); ++k)
      csv << r.displacement_m[k] << ',' << r.pressure_Pa[k] << '\n';
    std::printf("H/B %.3f, %s base, %s end, %g elements across B: limit pressure %.1f Pa, largest %.1f Pa, %ld steps\n",
                setup.layer_depth_m / setup.footing_width_m, base.c_str(), free_end ? "free" : "confined",
                elements_per_width, snow_fe::limit_pressure_Pa(r.displacement_m, r.pressure_Pa, setup.footing_width_m),
                r.largest_pressure_Pa, r.steps);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strip_bearing_fe: %s\n", e.what());
    return 2;
  }
}
