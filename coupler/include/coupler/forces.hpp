#pragma once
// The force decomposition of thesis chapter 2 (Browne 1974 as adopted there,
// Figure 2.1): traction F3, motion resistance F1, groove force F2, vertical
// pressure force F4, rolling-resistance force F5 = RRM / r, drawbar pull
// (eq. 2.1) and net longitudinal contact-pressure force (eq. 2.2), from the
// per-facet contact forces on the tyre. Definitions, signs and the choices made
// where the thesis is not explicit: docs/force_decomposition.md.
//
// Axes: ISO 8855 wheel axes (thesis 5.2.1), x forward (direction of travel),
// y left, z up. All forces act ON THE TYRE. F1, F5 are positive when they oppose
// travel; F2, F3, drawbar pull positive when they aid it.
#include <array>
#include <vector>

#include "coupler/friction.hpp"

namespace coupler {

// Contact forces on the tyre, one entry per contacted facet (structure of arrays).
struct FacetLoads {
  std::vector<FacetTag> tag;
  // The pressure part (the CFN part of thesis eq. 2.2, "due to contact pressure"):
  // as the terrain summed it, along each contact's direction (ContactLoads.pressure_*).
  std::vector<double> pressure_x_N, pressure_y_N, pressure_z_N;
  std::vector<double> friction_x_N, friction_y_N, friction_z_N;  // tangential (friction) part
  std::vector<double> centroid_x_m, centroid_y_m, centroid_z_m;
  std::vector<double> contact_area_m2;                           // > 0: facet in contact
  std::size_t size() const { return tag.size(); }
};

// What the decomposition needs of the wheel (thesis 5.2.3).
struct WheelInput {
  double rim_x_m = 0.0;               // rim node, longitudinal
  double rim_z_m = 0.0;               // rim node, vertical
  double reaction_moment_y_Nm = 0.0;  // RM2: moment the rim applies to the tyre about +y
  double rolling_radius_m = 0.0;      // r of eq. 5.1: L / (2 pi), zero-slip radius
};

enum class RrmSource {
  contact_pressure,  // RRM = sum Pz (x - x_rim): the shifted F4 of Figures 2.1, 2.2 (default)
  reaction_moment,   // RRM = RM2 at the rim node, as measured when towed (5.2.3)
};
enum class SinkageMeasure {
  contact_depth,  // undisturbed terrain top minus lowest contacted facet centroid (default)
  rim_drop,       // reference rim height minus rim height (Figures 5.5, 5.6, 6.13)
};

using TagSet = std::array<bool, cosim::kFacetTagCount>;  // indexed by FacetTag
// groove_wall and sipe_wall: the walls that hold the snow in the pattern (2.1.2).
TagSet default_groove_tags();
// The pattern's recesses: groove walls, groove floors and sipe walls. Where the
// terrain lifts the tyre (water under a grooved tread, docs/water.md) is read
// from F4 on these against F4 on the tread tops.
TagSet pattern_recess_tags();
TagSet tags_of(FacetTag tag);

// Choices the thesis leaves open (docs/force_decomposition.md, section "Choices").
struct DecompositionOptions {
  // Facet tags whose longitudinal pressure force is the groove force F2 (2.1.2);
  // all other tags give motion resistance F1 (2.1.1).
  TagSet groove_tags = default_groove_tags();
  RrmSource rrm_source = RrmSource::contact_pressure;
  SinkageMeasure sinkage = SinkageMeasure::contact_depth;
  double terrain_surface_z_m = 0.0;  // contact_depth: top of the undisturbed terrain
  double reference_rim_z_m = 0.0;    // rim_drop: rim height loaded on the undisturbed surface
};

// The result; field names follow ForceSummary (idl/cosim_topics.idl).
struct ForceDecomposition {
  double traction_force_N = 0.0;                   // F3
  double motion_resistance_N = 0.0;                // F1
  double groove_force_N = 0.0;                     // F2
  double vertical_pressure_force_N = 0.0;          // F4
  double vertical_pressure_force_tread_top_N = 0.0;  // the part of F4 on the tread tops
  double vertical_pressure_force_groove_N = 0.0;     // the part on groove walls and floors and sipe walls
  double rolling_resistance_moment_Nm = 0.0;       // RRM
  double pressure_centre_offset_m = 0.0;           // delta x: F4 centre ahead of the rim (0 if F4 = 0)
  double rolling_resistance_force_N = 0.0;         // F5
  double drawbar_pull_N = 0.0;                     // eq. 2.1
  double net_longitudinal_pressure_force_N = 0.0;  // eq. 2.2
  double traction_minus_rrf_N = 0.0;               // F3 - F5, the "traction" of Figures 6.4, 6.8, 6.14
  double sinkage_m = 0.0;
  double contact_area_m2 = 0.0;
};

// Throws cosim::Error if the arrays differ in length or hold non-finite or negative-area entries.
void validate(const FacetLoads& loads);

// F3 = sum_i T_x,i: longitudinal friction (tangential) force, thesis 2.1.3.
double traction_force(const FacetLoads& loads);
// {F1, F2}: F2 = sum_{i in G} P_x,i (2.1.2), F1 = -sum_{i not in G} P_x,i (2.1.1), G = groove tags.
struct PressureSplit {
  double motion_resistance_N = 0.0;
  double groove_force_N = 0.0;
};
PressureSplit split_longitudinal_pressure(const FacetLoads& loads, const TagSet& groove_tags);
// F4 = sum_i P_z,i: vertical force due to contact pressure, Figure 2.1.
double vertical_pressure_force(const FacetLoads& loads);
// The part of F4 on the facets whose tag is in `tags`.
double vertical_pressure_force(const FacetLoads& loads, const TagSet& tags);
// The parts add up (thesis eq. 2.2: each contact force is its pressure part plus
// its friction part): |sum over the facets of (pressure + friction) - total| [N],
// total the force the terrain puts on the tyre's nodes.
double decomposition_residual_N(const FacetLoads& loads, double total_x_N, double total_y_N, double total_z_N);
// RRM = sum_i P_z,i (x_i - x_rim) = F4 delta x, thesis 2.1.4 / Figure 2.2; > 0 opposes forward rolling.
double rolling_resistance_moment(const FacetLoads& loads, double rim_x_m);
// F5 = RRM / r, thesis 2.1.4 with r of eq. 5.1; throws unless r > 0.
double rolling_resistance_force(double rrm_Nm, double rolling_radius_m);
// Drawbar pull = F2 + F3 - F1 - F5, thesis eq. 2.1.
inline double drawbar_pull(double f1, double f2, double f3, double f5) { return f2 + f3 - f1 - f5; }
// Net longitudinal force due to contact pressure = -F1 + F2, thesis eq. 2.2.
inline double net_longitudinal_pressure_force(double f1, double f2) { return -f1 + f2; }
// Sum of contact_area over the facets (thesis Table 3.4, Figure 5.6).
double contact_area(const FacetLoads& loads);
// Lowest contacted facet centroid below the terrain top (0 with no contact), thesis 5.3, 6.2.
double contact_depth(const FacetLoads& loads, double terrain_surface_z_m);

// All of the above for one step.
ForceDecomposition decompose_forces(const FacetLoads& loads, const WheelInput& wheel,
                                    const DecompositionOptions& options = {});

}  // namespace coupler
