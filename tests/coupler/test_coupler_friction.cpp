// Friction coefficient per contact facet (coupler/friction.hpp) against the
// rules of the thesis: 0.3 tyre-snow (3.3, 6.1), 0.45 equivalent on the tread
// top of the tread with sipes (4.3, 4.4, 6.1), 0 against water (4.2, 4.3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <string>

#include "cosim/error.hpp"
#include "cosim/scene_io.hpp"
#include "coupler/friction.hpp"
#include "coupler/scene_settings.hpp"

using coupler::FacetTag;
using coupler::TerrainKind;

namespace {

const auto& kAllTags = cosim::kAllFacetTags;

// Expects `fn` to throw cosim::Error whose message contains `part`.
template <class Fn>
void expect_error(Fn fn, const std::string& part) {
  try {
    fn();
    ADD_FAILURE() << "no cosim::Error thrown (expected one mentioning '" << part << "')";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

// The rules of a scene whose coupling section leaves friction to the schema's
// defaults (configs/schema/scene.proto): the thesis's coefficients.
coupler::FrictionRules thesis_rules() {
  cosim::LoadedScene scene;
  cosim::fill_schema_defaults(*scene.message.mutable_coupling());
  return coupler::friction_rules(scene);
}

}  // namespace

TEST(CouplerFriction, SchemaDefaultsAreTheThesisCoefficients) {
  const coupler::FrictionRules rules = thesis_rules();
  EXPECT_EQ(rules.base_mu, 0.3);              // thesis 6.1 (Ella et al. 2013: ~0.3 without sipes)
  EXPECT_EQ(rules.sipe_equivalent_mu, 0.45);  // thesis 6.1 (~0.45 with sipes)
  EXPECT_TRUE(rules.tag_mu.empty());
}

TEST(CouplerFriction, SipeTreadTopGetsEquivalentCoefficientOnSnow) {
  const coupler::FrictionRules rules = thesis_rules();
  for (TerrainKind snow : {TerrainKind::snow_soft, TerrainKind::snow_hard}) {
    EXPECT_EQ(coupler::facet_mu(FacetTag::tread_top, true, snow, rules), 0.45);   // 6.1: tread top with sipes
    EXPECT_EQ(coupler::facet_mu(FacetTag::tread_top, false, snow, rules), 0.3);   // 6.1: block tread, smooth cap
    for (FacetTag t : kAllTags) {
      if (t != FacetTag::tread_top) {
        EXPECT_EQ(coupler::facet_mu(t, true, snow, rules), 0.3);  // "other surfaces 0.3"
      }
    }
  }
}

TEST(CouplerFriction, WaterIsFrictionlessWhateverTheRules) {
  coupler::FrictionRules rules = thesis_rules();
  coupler::add_tag_override(rules, "tread_top", 0.8);
  for (FacetTag t : kAllTags)
    for (bool sipes : {false, true}) EXPECT_EQ(coupler::facet_mu(t, sipes, TerrainKind::water, rules), 0.0);  // 4.2
}

TEST(CouplerFriction, RigidRoadUsesBaseCoefficientEvenWithSipes) {
  const coupler::FrictionRules rules = thesis_rules();  // 4.3: rubber on rigid surface 0.3; sipes modelled, not equivalent
  EXPECT_EQ(coupler::facet_mu(FacetTag::tread_top, true, TerrainKind::rigid_road, rules), 0.3);
}

TEST(CouplerFriction, OverridesWinOverSipeAndBaseRules) {
  coupler::FrictionRules rules = thesis_rules();
  coupler::add_tag_override(rules, "shoulder", 0.5);
  coupler::add_tag_override(rules, "tread_top", 0.6);
  EXPECT_EQ(coupler::facet_mu(FacetTag::shoulder, false, TerrainKind::snow_soft, rules), 0.5);
  EXPECT_EQ(coupler::facet_mu(FacetTag::tread_top, true, TerrainKind::snow_hard, rules), 0.6);
  EXPECT_EQ(coupler::facet_mu(FacetTag::groove_wall, true, TerrainKind::snow_hard, rules), 0.3);
}

TEST(CouplerFriction, FillsOneCoefficientPerFacet) {
  const std::vector<FacetTag> tags = {FacetTag::tread_top, FacetTag::groove_wall, FacetTag::tread_top,
                                      FacetTag::sidewall};
  const coupler::FrictionRules rules = thesis_rules();
  std::vector<double> mu;
  coupler::fill_facet_friction(tags, true, TerrainKind::snow_soft, rules, mu);
  EXPECT_EQ(mu, (std::vector<double>{0.45, 0.3, 0.45, 0.3}));
  coupler::fill_facet_friction(tags, false, TerrainKind::snow_soft, rules, mu);
  EXPECT_EQ(mu, (std::vector<double>{0.3, 0.3, 0.3, 0.3}));
  coupler::fill_facet_friction(tags, true, TerrainKind::water, rules, mu);
  EXPECT_EQ(mu, (std::vector<double>(4, 0.0)));
  // Subset, as SurfaceKinematics carries it: one entry per listed facet.
  coupler::fill_facet_friction(tags, {3, 0}, true, TerrainKind::snow_hard, rules, mu);
  EXPECT_EQ(mu, (std::vector<double>{0.3, 0.45}));
  expect_error([&] { coupler::fill_facet_friction(tags, {4}, true, TerrainKind::snow_hard, rules, mu); },
               "facet index 4 (entry 0) is out of range: the surface has 4 facets");
}

// What the coupler hands the terrain each exchange: the listed facets less the
// sipe walls, each with its coefficient, in the order listed. Exact: values are copied.
TEST(CouplerFriction, ListedFacetsKeepTheirCoefficientsAndLoseTheSipeWalls) {
  const std::vector<FacetTag> tags = {FacetTag::tread_top, FacetTag::sipe_wall, FacetTag::groove_wall,
                                      FacetTag::sipe_wall, FacetTag::sidewall};
  const std::vector<double> mu_of_facet = {0.45, 0.45, 0.3, 0.45, 0.25};
  std::vector<std::uint32_t> facets = {4, 3, 0, 1, 2};
  std::vector<double> mu = {9.0};  // whatever the sample held
  coupler::keep_facets_with_friction(tags, mu_of_facet, 7, facets, mu);
  EXPECT_EQ(facets, (std::vector<std::uint32_t>{4, 0, 2}));
  EXPECT_EQ(mu, (std::vector<double>{0.25, 0.45, 0.3}));
  facets.clear();
  coupler::keep_facets_with_friction(tags, mu_of_facet, 7, facets, mu);
  EXPECT_TRUE(facets.empty());
  EXPECT_TRUE(mu.empty());
  facets = {0, 5};
  expect_error([&] { coupler::keep_facets_with_friction(tags, mu_of_facet, 7, facets, mu); },
               "SurfaceKinematics of step 7: facet 5 is not in the surface mesh");
}

TEST(CouplerFriction, RejectsNegativeOrNonFiniteCoefficients) {
  coupler::FrictionRules rules;
  rules.base_mu = -0.1;
  expect_error([&] { coupler::validate(rules); }, "base_mu = -0.1 must be a finite value >= 0");
  rules = {};
  rules.sipe_equivalent_mu = std::nan("");
  expect_error([&] { coupler::validate(rules); }, "sipe_equivalent_mu");
  rules = {};
  rules.tag_mu[FacetTag::shoulder] = -1.0;
  std::vector<double> mu;
  expect_error([&] { coupler::fill_facet_friction({FacetTag::shoulder}, false, TerrainKind::snow_soft, rules, mu); },
               "override for tag shoulder");
  rules = {};
  expect_error([&] { coupler::add_tag_override(rules, "groove_wall", -0.2); }, "override for tag groove_wall");
  EXPECT_TRUE(rules.tag_mu.empty());
}

TEST(CouplerFriction, UnknownNamesAreRefusedWithAHint) {
  coupler::FrictionRules rules;
  expect_error([&] { coupler::add_tag_override(rules, "tread_tpo", 0.4); },
               "unknown facet tag 'tread_tpo'; known: tread_top groove_wall");
  expect_error([&] { coupler::facet_tag_from_name("sipe_walls"); }, "Did you mean 'sipe_wall'?");
  expect_error([&] { coupler::terrain_kind_from_name("snow_hrad"); }, "Did you mean 'snow_hard'?");
}

TEST(CouplerFriction, NamesRoundTrip) {
  for (FacetTag t : kAllTags) EXPECT_EQ(coupler::facet_tag_from_name(coupler::facet_tag_name(t)), t);
  for (TerrainKind k : {TerrainKind::snow_soft, TerrainKind::snow_hard, TerrainKind::water, TerrainKind::rigid_road})
    EXPECT_EQ(coupler::terrain_kind_from_name(coupler::terrain_kind_name(k)), k);
}
