// The strip footing on a layer over a rigid base (snow_fe/strip_fe.hpp) against
// the closed-form bearing factors of a cohesive frictionless layer
// (thin_layer_bearing_factors.csv, beside this file, with its sources).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "snow_fe/strip_fe.hpp"

namespace {

// Plane-strain shear strength c = d / sqrt(3) of the beta = 0 (von Mises) snow.
constexpr double kShearStrength_Pa = 10e3;

snow_fe::StripBearingSetup strip(double H_over_B, bool rough_base, double elements_per_width) {
  snow_fe::StripBearingSetup s;
  s.snow.youngs_modulus_Pa = 10e6;  // E / c = 1000, a stiff clay's rigidity
  s.snow.poisson_ratio = 0.3;
  s.snow.cohesion_Pa = std::sqrt(3.0) * kShearStrength_Pa;
  s.snow.friction_angle_rad = 0.0;
  s.snow.cap_eccentricity = 0.5;  // the cap far beyond any pressure of the test
  s.snow.hardening_pressure_Pa = {1e12, 2e12};
  s.snow.hardening_volumetric_plastic_strain = {0.0, 1.0};
  s.density_kg_per_m3 = 200.0;
  s.footing_width_m = 0.2;
  s.layer_depth_m = H_over_B * s.footing_width_m;
  s.layer_half_length_m = 3.0 * s.footing_width_m;
  s.element_size_m = s.footing_width_m / elements_per_width;
  s.rough_base = rough_base;
  s.footing_speed_m_per_s = 0.05;
  s.speed_ramp_time_s = 0.02;
  s.end_displacement_m = 0.05 * s.footing_width_m;
  return s;
}

TEST(StripFe, Explore) {
  const char* env = std::getenv("STRIP_EXPLORE");
  if (!env) GTEST_SKIP();
  const double hb_only = std::atof(env);
  for (double hb : {2.0, 1.0, 0.5, 0.4})
    for (bool rough : {true, false})
      for (double n : {10.0, 20.0}) {
        if (hb_only > 0 && hb != hb_only) continue;
        const auto r = snow_fe::run_strip_bearing(strip(hb, rough, n), 50);
        std::printf("H/B %.2f %s base, B/h %.0f: N_c plateau %.3f, largest %.3f, steps %ld\n", hb,
                    rough ? "rough" : "smooth", n, snow_fe::limit_pressure_Pa(r.displacement_m, r.pressure_Pa) / kShearStrength_Pa,
                    r.largest_pressure_Pa / kShearStrength_Pa, r.steps);
        for (std::size_t k = 0; k < r.pressure_Pa.size(); k += 5)
          std::printf("   d/B %.4f  N %.3f\n", r.displacement_m[k] / 0.2, r.pressure_Pa[k] / kShearStrength_Pa);
      }
}

}  // namespace
