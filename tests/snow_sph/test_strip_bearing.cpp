// A rigid rough strip pushed into a thin cohesive frictionless layer on a
// smooth rigid base, free to spread (configs/scenes/strip_bearing.textproto with
// the layer ending short of the box's wall), against the closed form: at
// H / B = 0.5 the bearing factor is exactly 2 (Hill's opposed dies of width
// equal to the plate's thickness; tests/snow_fe/thin_layer_bearing_factors.csv).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cosim/error.hpp"
#include "snow_sph/run.hpp"
#include "snow_sph/scene.hpp"
#include "test_support.hpp"

namespace {

constexpr double kFootingWidth_m = 0.2, kShearStrength_Pa = 10e3;  // the scene's B and d / sqrt(3)

// N_c = the largest footing pressure up to a settlement of B/40, over c
// (snow_fe::limit_pressure_Pa's rule), with `particles` through H = B h_over_b:
// on a smooth base free to spread (the layer ends 0.1 m short of the box's
// wall) or on a no-slip floor (`rough`).
double sph_bearing_factor(int particles, double h_over_b = 0.5, bool rough = false) {
  const double H = h_over_b * kFootingWidth_m, dx = H / particles, width = 3 * dx;
  auto num = [](double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
  };
  std::vector<std::string> sets = {"sph.particle_spacing_m=" + num(dx),
                                   "sph.container.max.y=" + num(width),
                                   "sph.container.max.z=" + num(H),
                                   "sph.blocks[0].region.max.y=" + num(width),
                                   "sph.blocks[0].region.max.z=" + num(H),
                                   "sph.rigid_bodies[0].initial_bottom_centre_m.y=" + num(width / 2),
                                   "sph.rigid_bodies[0].initial_bottom_centre_m.z=" + num(H),
                                   "time.end_time_s=0.1"};
  sets.push_back(rough ? "sph.container.floor.kind=NO_SLIP" : "sph.container.max.x=0.7");
  const auto scene =
      snow_sph::load_sph_scene(test_support::source_dir() + "/configs/scenes/strip_bearing.textproto", sets);
  snow_sph::RunOptions options;
  options.out_dir = testing::TempDir() + "strip_bearing_" + std::to_string(particles);
  options.quiet = true, options.write_vtk = false;
  snow_sph::run_scene(*scene, options);
  std::ifstream csv(options.out_dir + "/bodies.csv");
  std::string line;
  std::getline(csv, line);  // time_s, strip_z_m, strip_displacement_m, ..., strip_contact_force_z_N, ...
  double largest = 0.0;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
    if (v[2] <= kFootingWidth_m / 40.0) largest = std::max(largest, v[4] / (0.5 * kFootingWidth_m * width));
  }
  std::printf("SPH strip, H/B %.2f, %s, %d particles through H: N_c %.3f\n", h_over_b,
              rough ? "no-slip floor" : "smooth base, free to spread", particles, largest / kShearStrength_Pa);
  return largest / kShearStrength_Pa;
}

// The coarsest resolution of the rolling scenes' snow, 4 particles through the
// layer. Measured (scripts/strip_bearing_study.py): 2.431, 2.288, 2.205 at 4, 6,
// 10 particles through H (+21.5, +14.4, +10.3 %), the FE 2.553, 2.363, 2.258 at
// 5, 10, 20 elements through H; the limit rule's own bias is 5-6 % (the FE
// extrapolated to a zero element size: 2.13). 2 is also a strict lower bound
// (the column under the footing in uniaxial compression). 30 %: the confined
// layer bears 4.1-4.7, a rough floor more than 5, a strength read as d instead
// of d / sqrt(3) 3.5.
TEST(StripBearing, SmoothBaseHalfWidthLayerBearsTwiceItsStrength) {
  const double n_c = sph_bearing_factor(4);
  EXPECT_GT(n_c, 2.0);
  EXPECT_LT(n_c, 1.3 * 2.0);
}

// A rough base at H/B = 1: Prandtl's 2 + pi, exact (the mechanism, 0.707 B
// deep, fits in the layer). Needs the container's no-slip floor
// (sph.container.floor, issue 46 item 4): skipped, saying so, where the schema
// has none. Measured with it (scripts/strip_bearing_study.py): 4.937, 5.001,
// 5.029 at 4, 6, 10 particles through H (-4.0, -2.7, -2.2 %), below the exact
// value where the FE lies above it (5.702 at 10 elements through H), and
// converging to it. 10 %: the frictionless floor confined by the box's wall
// bears 4.5, a strength read as d instead of d / sqrt 3 8.9.
TEST(StripBearing, RoughBaseDeepLayerBearsPrandtl) {
  double n_c = 0.0;
  try {
    n_c = sph_bearing_factor(4, 1.0, true);
  } catch (const cosim::Error& e) {
    if (std::string(e.what()).find("floor") == std::string::npos) throw;
    GTEST_SKIP() << "the container has no floor contact yet: " << e.what();
  }
  EXPECT_NEAR(n_c, 5.1416, 0.10 * 5.1416);
}

}  // namespace
