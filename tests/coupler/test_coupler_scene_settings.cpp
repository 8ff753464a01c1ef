// What the coupler takes from a scene (coupler/scene_settings.hpp): the terrain
// the tyre meets, the friction rules and the tread's sipes (thesis 4.2-4.4, 6.1),
// and the window of the steady means with its fallback to the FE body's.
// Exact comparisons throughout: every value is read or copied, none computed.
#include <gtest/gtest.h>

#include <string>

#include "cosim/error.hpp"
#include "cosim/scene_io.hpp"
#include "coupler/scene_settings.hpp"

namespace sc = cosim::scene;
using coupler::TerrainKind;

namespace {

// A scene with one SPH block of each given material.
cosim::LoadedScene scene_with_blocks(std::initializer_list<const char*> materials) {
  cosim::LoadedScene loaded;
  for (const std::string m : materials) {
    auto* block = loaded.message.mutable_sph()->add_blocks();
    if (m == "water") block->mutable_material()->mutable_water();
    if (m == "soft") block->mutable_material()->mutable_snow()->set_snow_class(sc::SOFT_SNOW);
    if (m == "hard") block->mutable_material()->mutable_snow()->set_snow_class(sc::HARD_SNOW);
  }
  cosim::fill_schema_defaults(*loaded.message.mutable_coupling());
  return loaded;
}

}  // namespace

TEST(CouplerSceneSettings, TerrainIsWaterThenHardSnowThenSoftSnow) {
  EXPECT_EQ(coupler::terrain_kind(scene_with_blocks({}).message), TerrainKind::snow_soft);
  EXPECT_EQ(coupler::terrain_kind(scene_with_blocks({"soft"}).message), TerrainKind::snow_soft);
  EXPECT_EQ(coupler::terrain_kind(scene_with_blocks({"soft", "hard"}).message), TerrainKind::snow_hard);
  EXPECT_EQ(coupler::terrain_kind(scene_with_blocks({"hard", "water", "soft"}).message), TerrainKind::water);
}

TEST(CouplerSceneSettings, FrictionRulesComeFromTheCouplingSection) {
  cosim::LoadedScene loaded = scene_with_blocks({"hard"});
  auto* c = loaded.message.mutable_coupling();
  c->set_base_friction_coefficient(0.2);
  auto* o = c->add_tag_friction();
  o->set_tag("shoulder"), o->set_friction_coefficient(0.7);
  const coupler::FrictionRules rules = coupler::friction_rules(loaded);
  EXPECT_EQ(rules.base_mu, 0.2);
  EXPECT_EQ(rules.sipe_equivalent_mu, 0.45);  // the schema's default, thesis 6.1
  ASSERT_EQ(rules.tag_mu.size(), 1u);
  EXPECT_EQ(rules.tag_mu.at(coupler::FacetTag::shoulder), 0.7);
  o->set_tag("shoulderz");
  try {
    coupler::friction_rules(loaded);
    ADD_FAILURE() << "an unknown tag was accepted";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find("coupling.tag_friction"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("unknown facet tag 'shoulderz'"), std::string::npos) << e.what();
  }
}

TEST(CouplerSceneSettings, OnlyTheThesisSipesGetTheEquivalentCoefficient) {
  cosim::LoadedScene loaded = scene_with_blocks({"soft"});
  auto* tread = loaded.message.mutable_tyre()->mutable_tread();
  tread->set_variant(sc::BLOCK_SIPES);
  coupler::SceneFriction f = coupler::scene_friction(loaded);
  EXPECT_TRUE(f.tread_has_sipes);
  EXPECT_EQ(f.terrain, TerrainKind::snow_soft);
  EXPECT_EQ(coupler::friction_summary(f)["sipe_treatment"], "equivalent coefficient on the tread top (thesis 6.1)");
  tread->set_variant(sc::BLOCK_SIPES_MESHED);  // slits in the mesh: the base coefficient on the tread top
  f = coupler::scene_friction(loaded);
  EXPECT_FALSE(f.tread_has_sipes);
  EXPECT_EQ(coupler::friction_summary(f)["sipe_treatment"], "slits in the mesh, base coefficient");
  tread->set_variant(sc::SMOOTH);
  EXPECT_EQ(coupler::friction_summary(coupler::scene_friction(loaded))["sipe_treatment"], "none");
  EXPECT_EQ(coupler::friction_summary(f)["base"], 0.3);
  EXPECT_EQ(coupler::friction_summary(f)["terrain"], "snow_soft");
}

TEST(CouplerSceneSettings, AveragingWindowFallsBackToTheFeBodys) {
  sc::Scene scene;
  scene.mutable_tyre()->mutable_stages()->set_average_last_s(0.02);
  EXPECT_EQ(coupler::averaging_window_s(scene), 0.02);  // the tyre's stages'
  scene.mutable_tread_block()->set_average_last_s(0.03);
  EXPECT_EQ(coupler::averaging_window_s(scene), 0.03);  // a tread block is the FE body
  scene.mutable_coupling()->set_average_last_s(0.01);
  EXPECT_EQ(coupler::averaging_window_s(scene), 0.01);  // the coupling's own wins
  EXPECT_EQ(coupler::averaging_window_s(sc::Scene()), 0.0);  // none anywhere: the whole run
}
