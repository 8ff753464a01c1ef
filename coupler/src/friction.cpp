// Friction coefficient per contact facet (thesis 4.2-4.4, 6.1); see friction.hpp.
#include "coupler/friction.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cosim/error.hpp"
#include "cosim/strings.hpp"

namespace coupler {

namespace {

constexpr TerrainKind kTerrains[] = {TerrainKind::snow_soft, TerrainKind::snow_hard, TerrainKind::water,
                                     TerrainKind::rigid_road};

void check_mu(double mu, const std::string& what) {
  if (!std::isfinite(mu) || mu < 0.0) {
    std::ostringstream msg;
    msg << "friction: " << what << " = " << mu << " must be a finite value >= 0";
    throw cosim::Error(msg.str());
  }
}

bool is_snow(TerrainKind t) { return t == TerrainKind::snow_soft || t == TerrainKind::snow_hard; }

}  // namespace

const char* terrain_kind_name(TerrainKind kind) {
  switch (kind) {
    case TerrainKind::snow_soft: return "snow_soft";
    case TerrainKind::snow_hard: return "snow_hard";
    case TerrainKind::water: return "water";
    case TerrainKind::rigid_road: return "rigid_road";
  }
  return "unknown";
}

TerrainKind terrain_kind_from_name(const std::string& name) {
  return cosim::value_from_name(name, kTerrains, terrain_kind_name, "terrain kind");
}

void validate(const FrictionRules& rules) {
  check_mu(rules.base_mu, "base_mu");
  check_mu(rules.sipe_equivalent_mu, "sipe_equivalent_mu");
  for (const auto& [tag, mu] : rules.tag_mu) check_mu(mu, std::string("override for tag ") + facet_tag_name(tag));
}

void add_tag_override(FrictionRules& rules, const std::string& tag_name, double mu) {
  const FacetTag tag = facet_tag_from_name(tag_name);
  check_mu(mu, "override for tag " + tag_name);
  rules.tag_mu[tag] = mu;
}

double facet_mu(FacetTag tag, bool tread_has_sipes, TerrainKind terrain, const FrictionRules& rules) {
  if (terrain == TerrainKind::water) return 0.0;  // thesis 4.2, 4.3
  if (const auto it = rules.tag_mu.find(tag); it != rules.tag_mu.end()) return it->second;
  if (tread_has_sipes && tag == FacetTag::tread_top && is_snow(terrain))
    return rules.sipe_equivalent_mu;  // thesis 4.4, 6.1
  return rules.base_mu;               // thesis 3.3, 4.3, 6.1
}

void fill_facet_friction(const std::vector<FacetTag>& tags, bool tread_has_sipes, TerrainKind terrain,
                         const FrictionRules& rules, std::vector<double>& mu) {
  validate(rules);
  mu.resize(tags.size());
  for (std::size_t i = 0; i < tags.size(); ++i) mu[i] = facet_mu(tags[i], tread_has_sipes, terrain, rules);
}

void fill_facet_friction(const std::vector<FacetTag>& tags, const std::vector<std::uint32_t>& facets,
                         bool tread_has_sipes, TerrainKind terrain, const FrictionRules& rules,
                         std::vector<double>& mu) {
  validate(rules);
  mu.resize(facets.size());
  for (std::size_t k = 0; k < facets.size(); ++k) {
    if (facets[k] >= tags.size())
      throw cosim::Error("friction: facet index " + std::to_string(facets[k]) + " (entry " + std::to_string(k) +
                         ") is out of range: the surface has " + std::to_string(tags.size()) + " facets");
    mu[k] = facet_mu(tags[facets[k]], tread_has_sipes, terrain, rules);
  }
}

void keep_facets_with_friction(const std::vector<FacetTag>& tags, const std::vector<double>& mu_of_facet,
                               std::uint64_t step, std::vector<std::uint32_t>& facets,
                               std::vector<double>& friction_coefficient) {
  std::size_t kept = 0;
  friction_coefficient.resize(facets.size());
  for (std::size_t i = 0; i < facets.size(); ++i) {
    const auto f = facets[i];
    if (f >= mu_of_facet.size())
      throw cosim::Error("SurfaceKinematics of step " + std::to_string(step) + ": facet " + std::to_string(f) +
                         " is not in the surface mesh");
    if (tags[f] == FacetTag::sipe_wall) continue;
    facets[kept] = f, friction_coefficient[kept] = mu_of_facet[f], ++kept;
  }
  facets.resize(kept), friction_coefficient.resize(kept);
}

}  // namespace coupler
