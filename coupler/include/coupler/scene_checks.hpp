#pragma once
// Checks of a scene's `coupling` section and of what a coupled run needs from
// the other sections, with file:line:field messages (cosim check runs them).
#include "cosim/scene_io.hpp"

namespace coupler {

// Adds one line per problem to `report`. Scenes without a coupling section pass.
void validate_coupling_scene(const cosim::LoadedScene& scene, cosim::ValidationReport& report);

}  // namespace coupler
