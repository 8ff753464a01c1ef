// What the coupler takes from a scene; see scene_settings.hpp.
#include "coupler/scene_settings.hpp"

#include "cosim/error.hpp"

namespace coupler {

namespace sc = cosim::scene;

TerrainKind terrain_kind(const sc::Scene& scene) {
  bool hard = false;
  for (const auto& b : scene.sph().blocks()) {
    if (b.material().has_water()) return TerrainKind::water;
    hard = hard || b.material().snow().snow_class() == sc::HARD_SNOW;
  }
  return hard ? TerrainKind::snow_hard : TerrainKind::snow_soft;
}

FrictionRules friction_rules(const cosim::LoadedScene& loaded) {
  const auto& c = loaded.message.coupling();
  FrictionRules rules;
  rules.base_mu = c.base_friction_coefficient();
  rules.sipe_equivalent_mu = c.sipe_equivalent_friction_coefficient();
  for (int i = 0; i < c.tag_friction_size(); ++i) {
    try {
      add_tag_override(rules, c.tag_friction(i).tag(), c.tag_friction(i).friction_coefficient());
    } catch (const cosim::Error& e) {
      throw cosim::Error(loaded.locator().child("coupling").where("tag_friction") + ": " + e.what());
    }
  }
  validate(rules);
  return rules;
}

SceneFriction scene_friction(const cosim::LoadedScene& loaded) {
  SceneFriction f;
  f.rules = friction_rules(loaded);
  f.terrain = terrain_kind(loaded.message);
  const auto variant = loaded.message.tyre().tread().variant();
  f.tread_has_sipes = variant == sc::BLOCK_SIPES;
  f.sipe_treatment = f.tread_has_sipes                     ? "equivalent coefficient on the tread top (thesis 6.1)"
                     : variant == sc::BLOCK_SIPES_MESHED ? "slits in the mesh, base coefficient"
                                                           : "none";
  return f;
}

nlohmann::json friction_summary(const SceneFriction& f) {
  return {{"terrain", terrain_kind_name(f.terrain)},
          {"tread_has_sipes", f.tread_has_sipes},
          {"sipe_treatment", f.sipe_treatment},
          {"base", f.rules.base_mu},
          {"sipe_equivalent_on_tread_top", f.rules.sipe_equivalent_mu}};
}

double averaging_window_s(const sc::Scene& scene) {
  const double coupling_window_s = scene.coupling().average_last_s();
  if (coupling_window_s > 0) return coupling_window_s;
  return scene.has_tread_block() ? scene.tread_block().average_last_s() : scene.tyre().stages().average_last_s();
}

}  // namespace coupler
