#pragma once
// What the coupler takes from a scene besides its checks (scene_checks.hpp):
// how friction is decided (the terrain, the rules, the tread's sipes) and the
// window of the steady means. The values come from the scene as loaded, with
// the schema's defaults filled (configs/schema/scene.proto); none is restated here.
#include <nlohmann/json.hpp>

#include "coupler/friction.hpp"
#include "cosim/scene_io.hpp"

namespace coupler {

// The terrain the tyre meets, from its material (the scene's blocks, filled by
// coupling.terrain): water if any block is water, else hard snow if any is, else soft snow.
TerrainKind terrain_kind(const cosim::scene::Scene& scene);

// The rules of coupling.base_friction_coefficient, sipe_equivalent_friction_coefficient
// and tag_friction, validated; a bad override throws naming its file:line.
FrictionRules friction_rules(const cosim::LoadedScene& loaded);

// Everything friction_rules and the tread decide about a facet's coefficient.
struct SceneFriction {
  FrictionRules rules;
  TerrainKind terrain = TerrainKind::snow_soft;
  // The thesis's sipes (BLOCK_SIPES) are the equivalent coefficient on the tread
  // top; sipes cut into the mesh (BLOCK_SIPES_MESHED) never get it on top of the slits.
  bool tread_has_sipes = false;
  const char* sipe_treatment = "none";  // for the summary
};
SceneFriction scene_friction(const cosim::LoadedScene& loaded);

// The summary's "friction" section.
nlohmann::json friction_summary(const SceneFriction& friction);

// The window of the steady means [s] (thesis 6.1: results "taken at the steady
// state region"): coupling.average_last_s, or where the coupling names none
// (0), the FE body's own: the tread block's average_last_s, else the tyre's
// stages'. A derived default, so it lives here and not in the schema: the
// coupler's means then cover the same window as the body's own.
double averaging_window_s(const cosim::scene::Scene& scene);

}  // namespace coupler
