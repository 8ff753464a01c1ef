#pragma once
// A tread block as an FE body of its own (thesis 3.4, the tread indentation;
// scene `tread_block`): a hexahedral mesh of ribs over a solid base, its top
// face held by a reference node that pushes it into the terrain along a
// prescribed path. The mesh is a Mesh3D, so the tyre's model, explicit step
// and terrain port (model3d.hpp, solver3d.hpp, terrain_port.hpp) run it as
// they run the tyre: the top nodes are the "rim" nodes.
#include <vector>

#include "cosim/scene_io.hpp"
#include "tyre_fe/axisym.hpp"
#include "tyre_fe/mesh.hpp"
#include "tyre_fe/tread_block_mesh.hpp"

namespace tyre_fe {

// The reference node's path: down by total_m (from the start gap to the
// depth) at speed v, the speed ramped in and out over ramp_s each with a
// smoothstep (cosim/ramp.hpp), so the displacement is
//   d(t) = v T (u^3 - u^4 / 2), u = t / T          while ramping in,
// then linear, then mirrored about the end; held at total_m afterwards.
struct PushPath {
  double total_m = 0.0, speed_m_per_s = 0.0, ramp_s = 0.0;
  double end_s() const;  // when total_m is reached: total / v + ramp
};
double push_displacement_m(const PushPath& p, double t_s);

// Sliding instead of pushing (thesis 4.3, a block on a water film on a road):
// the reference node carries the load (ramped in over load_ramp_s, z free),
// holds it for settle_s, then slides along x at speed_m_per_s (ramped in over
// speed_ramp_s) for slide_s; the results average over its last average_s.
struct SlideSpec {
  double load_N = 0.0, load_ramp_s = 0.0, settle_s = 0.0;
  double speed_m_per_s = 0.0, speed_ramp_s = 0.0, slide_s = 0.0, average_s = 0.0;
  double start_s() const { return load_ramp_s + settle_s; }
  double end_s() const { return start_s() + slide_s; }
};

// Everything the block run needs, from a validated scene.
struct TreadBlockSetup {
  TreadBlockGeometry geometry;
  TyreMaterials materials;  // the block's material in Region::tread
  PushPath path;
  double initial_gap_m = 0.0, push_depth_m = 0.0, hold_s = 0.0;
  double reference_node_mass_kg = 0.0;
  SlideSpec slide;
  bool sliding() const { return slide.load_N > 0.0; }  // the slide replaces the push path
};
// Ranges and rules, each failure naming the scene's file, line and field.
void validate_tread_block_scene(const cosim::LoadedScene& scene, cosim::ValidationReport& report);
TreadBlockSetup tread_block_setup(const cosim::LoadedScene& scene);

}  // namespace tyre_fe
