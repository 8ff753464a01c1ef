#pragma once
// A rigid strip footing pushed into a layer on a rigid base, on the Lagrangian
// plane-strain mesh of axisym_fe.hpp (Geometry::plane_strain) with the snow's
// mdpc_update: the finite-element side of the thin-layer bearing check
// (docs/validation.md, "A thin layer that bears"; the SPH side is
// configs/scenes/strip_bearing.textproto).
//
// Half model (the strip's centre line x = 0 a symmetry plane): a layer of depth
// H and half-length L; the footing (width B) is the top nodes with x <= B/2,
// their velocity prescribed (down at the footing's speed, none sideways: a rough
// footing). The base is fixed (rough) or a roller (smooth); the far end x = L is
// a roller. The speed rises from zero along a smootherstep ramp, so that the
// loading is quasi-static; the footing's pressure is the snow's force on its
// nodes over B/2. No gravity: with a cohesive frictionless (beta = 0, von Mises)
// material the limit pressure is then N_c c, c = d / sqrt(3) the plane-strain
// shear strength (Hill 1950, The Mathematical Theory of Plasticity, ch. VI: in
// plane strain with an incompressible flow the out-of-plane stress is the mean
// of the in-plane ones and Mises' criterion reads |tau_max| = d / sqrt(3)).
#include <vector>

#include "cosim/scene_io.hpp"
#include "snow_sph/mdpc.hpp"

namespace snow_fe {

struct StripBearingSetup {
  snow_sph::MdpcParameters snow;
  double density_kg_per_m3 = 0.0;
  double footing_width_m = 0.0;      // B
  double layer_depth_m = 0.0;        // H
  double layer_half_length_m = 0.0;  // L, from the centre line
  double element_size_m = 0.0;       // target; x = B/2 is always a node line
  bool rough_base = true;            // fixed base; false: a roller
  // The layer's end x = L: a roller (confined, as a box's wall) or free (a
  // layer that may spread: on a smooth base its outer part then slides away
  // freely, Hill's opposed-dies problem; docs/validation.md).
  bool confined_end = true;
  double footing_speed_m_per_s = 0.0;
  double speed_ramp_time_s = 0.0;
  double end_displacement_m = 0.0;
  double time_step_fraction = 0.4;  // of sqrt(2) A / diagonal / c, see stable_time_step
};

struct StripBearingResult {
  std::vector<double> displacement_m;  // footing's, downwards, one per output point
  std::vector<double> pressure_Pa;     // mean pressure under the footing at that point
  double largest_pressure_Pa = 0.0;
  double smallest_jacobian_ratio = 1.0;
  long steps = 0;
};

// Runs to end_displacement_m with `outputs` equally spaced output points.
// Throws cosim::Error for a bad setup or an inverted element.
StripBearingResult run_strip_bearing(const StripBearingSetup& setup, int outputs = 100);

// The limit pressure read from a pressure-settlement curve: the largest
// pressure up to a settlement of B/40. With E / c = 1000 the elastic settlement
// at the limit is about q B / E = 0.5 % of B, so the plastic mechanism has
// formed by B/40, while the layer's thinning and the footing's embedment (which
// the small-deformation closed forms leave out) are still 2.5 % of B; beyond, a
// Lagrangian mesh's curve keeps rising with them and a particle layer's may
// fall. The SPH study applies the same rule (scripts/strip_bearing_study.py).
double limit_pressure_Pa(const std::vector<double>& displacement_m, const std::vector<double>& pressure_Pa,
                         double footing_width_m);

// From the SPH strip scene (configs/scenes/strip_bearing.textproto): its
// snow, the layer (its block's height and x-length), the strip (its
// width twice the x of the body's rim, its speed), the end displacement
// (speed x end time). The base is given (the scene's floor is the smooth one);
// the speed ramps in over a tenth of the run. Throws cosim::Error naming the
// field when the scene is not a strip scene.
StripBearingSetup strip_setup_from_scene(const cosim::LoadedScene& scene, bool rough_base, double element_size_m);

}  // namespace snow_fe
