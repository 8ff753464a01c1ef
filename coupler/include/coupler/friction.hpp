#pragma once
// Friction coefficient of each tyre contact facet, decided by the coupler from
// the facet's tag, the tread variant and the terrain (thesis 4.3, 4.4, 6.1).
//
// Rules, in order of precedence (thesis section cited on each):
//  1. terrain water: mu = 0 on every facet ("the friction coefficient between
//     water and all other components are taken as zero", 4.2 and 4.3);
//  2. a per-tag override, if the rules hold one for the facet's tag;
//  3. tread with sipes, tag tread_top, snow terrain: the equivalent coefficient
//     (0.45) that stands in for unmodelled sipes and the melt-water film (4.4, 6.1);
//  4. otherwise the base coefficient (0.3; tyre-snow 3.3, 6.1; rubber-rigid 4.3).
// Rule 3 is limited to snow: the equivalent coefficient is defined "between
// tread top surface and snow" (6.1); on a rigid road the thesis used 0.3 (4.3).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cosim/facet_tag.hpp"

namespace coupler {

// The project's one facet-tag enum and its names (cosim/facet_tag.hpp).
using cosim::FacetTag;
using cosim::facet_tag_from_name;
using cosim::facet_tag_name;

// What the tyre runs on (thesis 3.1/6.2 soft snow, 6.3 hard snow, 4.2 water, 5.2.3 road).
enum class TerrainKind { snow_soft, snow_hard, water, rigid_road };

// The coefficients from which each facet's mu is decided (rules 1-4 above).
// Their values come from the scene (coupler/scene_settings.hpp friction_rules),
// whose schema holds the thesis's as defaults (configs/schema/scene.proto).
struct FrictionRules {
  double base_mu = 0.0;             // coupling.base_friction_coefficient (thesis 6.1: 0.3, Ella et al. 2013)
  double sipe_equivalent_mu = 0.0;  // coupling.sipe_equivalent_friction_coefficient (thesis 6.1: 0.45)
  std::map<FacetTag, double> tag_mu;  // per-tag overrides (rule 2)
};

// "snow_soft", "snow_hard", "water", "rigid_road".
const char* terrain_kind_name(TerrainKind kind);
TerrainKind terrain_kind_from_name(const std::string& name);

// Throws cosim::Error if any coefficient is negative or not finite.
void validate(const FrictionRules& rules);
// Adds an override parsed from strings (config files); validates name and mu.
void add_tag_override(FrictionRules& rules, const std::string& tag_name, double mu);

// mu of one facet by rules 1-4 (thesis 4.2-4.4, 6.1).
double facet_mu(FacetTag tag, bool tread_has_sipes, TerrainKind terrain, const FrictionRules& rules);

// mu[i] = facet_mu(tags[i], ...) for every facet; validates the rules first.
void fill_facet_friction(const std::vector<FacetTag>& tags, bool tread_has_sipes, TerrainKind terrain,
                         const FrictionRules& rules, std::vector<double>& mu);

// The same for a subset: mu[k] for facet facets[k] of `tags` (SurfaceKinematics
// carries one coefficient per listed facet). Throws on an index out of range.
void fill_facet_friction(const std::vector<FacetTag>& tags, const std::vector<std::uint32_t>& facets,
                         bool tread_has_sipes, TerrainKind terrain, const FrictionRules& rules,
                         std::vector<double>& mu);

// The facets of one exchange handed on to the terrain, each with its mu: the
// listed `facets` (indices into the surface) lose their sipe walls, and
// `friction_coefficient` gets mu_of_facet[f] for each facet f kept, in order.
// Sipe walls are not handed on: a sipe is a slit (0.6 mm) that no particle
// enters, and its effect on the snow is the tread top's equivalent coefficient
// (thesis 4.4, 6.1); particles would otherwise be caught between its two
// coincident walls. `tags` and `mu_of_facet` cover every surface facet. Throws
// cosim::Error naming the SurfaceKinematics of `step` for a facet not in the surface.
void keep_facets_with_friction(const std::vector<FacetTag>& tags, const std::vector<double>& mu_of_facet,
                               std::uint64_t step, std::vector<std::uint32_t>& facets,
                               std::vector<double>& friction_coefficient);

}  // namespace coupler
