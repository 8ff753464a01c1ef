// The strip footing on a layer over a rigid base on the plane-strain Lagrangian
// mesh (snow_fe/strip_fe.hpp) against the closed-form bearing factors of a
// cohesive frictionless layer (thin_layer_bearing_factors.csv, beside this
// file, with its sources and the argument for each value), with the SPH
// strip scene's snow (configs/scenes/strip_bearing.textproto: beta = 0, the
// von Mises limit, c = d / sqrt(3) = 10 kPa in plane strain).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "snow_fe/strip_fe.hpp"
#include "snow_sph/scene.hpp"
#include "test_support.hpp"

namespace {

constexpr double kShearStrength_Pa = 10e3;  // the scene's d / sqrt(3)

// N_c of the data file for (H/B, base, kind); fails the test if absent.
double closed_form(double h_over_b, const std::string& base, const std::string& kind) {
  std::ifstream f(test_support::source_dir() + "/tests/snow_fe/thin_layer_bearing_factors.csv");
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("H_over_B", 0) == 0) continue;
    std::stringstream ss(line);
    std::string hb, b, nc, k;
    std::getline(ss, hb, ','), std::getline(ss, b, ','), std::getline(ss, nc, ','), std::getline(ss, k, ',');
    if (std::abs(std::stod(hb) - h_over_b) < 1e-9 && b == base && k == kind) return std::stod(nc);
  }
  ADD_FAILURE() << "no " << kind << " for H/B " << h_over_b << ", " << base;
  return 0.0;
}

// N_c = q_u / c of the scene's strip on a layer of H/B with the given base.
double fe_bearing_factor(double h_over_b, bool rough_base, bool confined_end, double elements_per_width) {
  const double H = 0.2 * h_over_b;
  const auto scene = snow_sph::load_sph_scene(
      test_support::source_dir() + "/configs/scenes/strip_bearing.textproto",
      {"sph.container.max.z=" + std::to_string(H), "sph.blocks[0].region.max.z=" + std::to_string(H),
       "sph.rigid_bodies[0].initial_bottom_centre_m.z=" + std::to_string(H)});
  auto setup = snow_fe::strip_setup_from_scene(*scene, rough_base, 0.0);
  setup.element_size_m = setup.footing_width_m / elements_per_width;
  setup.confined_end = confined_end;
  setup.end_displacement_m = setup.footing_width_m / 40.0;  // as far as the limit is read
  const auto r = snow_fe::run_strip_bearing(setup, 50);
  const double n_c =
      snow_fe::limit_pressure_Pa(r.displacement_m, r.pressure_Pa, setup.footing_width_m) / kShearStrength_Pa;
  std::printf("FE strip: H/B %.2f, %s base, %s end, B/h %.0f: N_c %.3f (%ld steps)\n", h_over_b,
              rough_base ? "rough" : "smooth", confined_end ? "confined" : "free", elements_per_width, n_c, r.steps);
  return n_c;
}

// The limit read at B/40 (snow_fe::limit_pressure_Pa) carries a bias of its
// own: the layer's thinning and the footing's embedment up to B/40 and the
// rounded elastic-plastic knee. Measured: the FE's N_c extrapolated to a zero
// element size lies 5-6 % above the closed forms below (5.41 against 2 + pi,
// 2.13 against 2). Displacement-based elements overestimate a limit load and
// converge to it from above, so each case is also checked against the
// closed form as a lower limit.

// Prandtl's 2 + pi on a rough base at H/B = 1 (the mechanism, 0.707 B deep,
// fits in the layer: exact). Measured at 10, 20, 40 elements across B: 5.702,
// 5.540, 5.469 (+10.9, +7.7, +6.4 %; docs/validation.md). 15 %: a plane-strain defect (a hoop term
// left in, or a wrong out-of-plane rate) or a strength read as d instead of
// d / sqrt(3) moves N_c by 18 % (the circle's 6.05) to 73 %.
TEST(StripFe, RoughBaseDeepLayerBearsPrandtl) {
  const double exact = closed_form(1.0, "rough", "exact");
  const double n_c = fe_bearing_factor(1.0, true, true, 10.0);
  EXPECT_GT(n_c, exact);
  EXPECT_LT(n_c, 1.15 * exact);
}

// A smooth base and a layer free to spread at H/B = 0.5: exactly 2 (the
// layer's outer part slides away on the frictionless base for nothing).
// Measured at 10, 20, 40 elements across B: 2.544, 2.358, 2.258 (+27, +18,
// +13 %; 5, 10, 20 elements through H). 25 % at 20 across B: the same layer
// held by a wall at 3B bears 4.7 (the confined case), a rough base more than 5.
TEST(StripFe, SmoothBaseFreeLayerBearsTwiceItsStrength) {
  const double exact = closed_form(0.5, "smooth_free", "exact");
  const double n_c = fe_bearing_factor(0.5, false, false, 20.0);
  EXPECT_GT(n_c, exact);
  EXPECT_LT(n_c, 1.25 * exact);
}

}  // namespace
