#pragma once
// Checks of a scene's `coupling` section and of what a coupled run needs from
// the other sections, with file:line:field messages (cosim check runs them);
// and what the coupler reads from the terrain's section.
#include "cosim/scene_io.hpp"

namespace coupler {

// Adds one line per problem to `report`. Scenes without a coupling section pass.
void validate_coupling_scene(const cosim::LoadedScene& scene, cosim::ValidationReport& report);

// The top of the undisturbed terrain, the sinkage's datum (docs/force_decomposition.md):
// the highest top of the particles of the scene's SPH blocks, which is below a
// block's region when the spacing does not divide its height
// (cosim/particle_lattice.hpp); 0 for a scene without blocks.
double terrain_surface_z_m(const cosim::scene::Scene& scene);

}  // namespace coupler
