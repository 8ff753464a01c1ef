#pragma once
// Tyre geometry: a cross-section generated from a size designation (or imported
// from an Abaqus input deck) and the 3D mesh revolved from it with a tread pitch.
#include <string>
#include <vector>

#include "tyre_fe/mesh.hpp"

namespace tyre_fe {

// ETRTO size designation, e.g. 235/75R15: section width 235 mm, aspect ratio 75 %,
// rim diameter 15 in.
struct TyreSize {
  double section_width_m = 0.235;
  double aspect_ratio = 0.75;
  double rim_diameter_m = 15 * 0.0254;
};
// Parses "235/75R15" (also "P235/75R15", "235/75 R 15"); throws cosim::Error.
TyreSize parse_tyre_size(const std::string& designation);

// Mesh density of the generated cross-section.
struct CrossSectionMesh {
  double target_element_size_m = 0.008;  // along the contour
  int tread_layers = 3;                  // elements through the tread thickness
};

enum class TreadVariant { smooth, rib, block, block_sipes };

// The tread pattern: one pitch, repeated `pitch_count` times around the tyre.
struct TreadPattern {
  TreadVariant variant = TreadVariant::smooth;
  double tread_width_m = 0.0;      // 0: 80 % of the section width
  double groove_depth_m = 0.010;   // non-skid depth (tread thickness above the base)
  double tread_base_m = 0.003;     // rubber under the groove bottoms
  // rib, block, block_sipes: circumferential grooves, lateral centres y [m] and width
  std::vector<double> circumferential_groove_y_m;
  double circumferential_groove_width_m = 0.010;
  // block, block_sipes: lateral grooves, one per pitch, width along the circumference
  int pitch_count = 60;
  double lateral_groove_width_m = 0.008;
  // block_sipes: sipes (slits across each block, parallel to the lateral grooves)
  int sipes_per_block = 2;
  double sipe_width_m = 0.0006;
  double sipe_depth_m = 0.007;
  // circumferential elements per pitch (smooth and rib: per 360/pitch_count deg)
  int elements_per_pitch = 4;
};

// Cross-section of a radial passenger tyre from its size (regions of thesis
// figure 5.3). The tread layers follow the pattern's groove layout so that 3D
// grooves fall on element boundaries: the edges of every circumferential groove
// and the tread edges are node lines (whatever the variant), and the groove
// bottom is a layer boundary at groove_depth_m (needs tread_layers >= 2). A
// structured mesh: stations along the carcass from bead seat to bead seat, the
// same layers at each (liner, ply, belt-1 layer, belt-2 layer, tread_layers rubber
// layers). Shape and dimensions: src/cross_section_profile.cpp. Throws
// cosim::Error for sizes or patterns it cannot mesh.
CrossSection make_cross_section(const TyreSize& size, const TreadPattern& pattern,
                                const CrossSectionMesh& mesh);

// Cross-section from an Abaqus input deck: *NODE (x = r, y = axial), *ELEMENT of
// type CGAX4, CGAX4R, CAX4, CAX4R, *ELSET named after the regions (names matched
// case-insensitively, e.g. TREAD, SIDEWALL, BELT_1 ...). Errors name file:line.
// (What else is accepted, and the fallbacks for rim nodes, the inner liner and the
// tread centre, is listed at the top of src/abaqus_import.cpp.)
CrossSection import_abaqus_cross_section(const std::string& inp_path, double tread_half_width_m);

// Writes the cross-section as an Abaqus input deck that import_abaqus_cross_section
// reads back unchanged: *NODE (r, y) and one *ELEMENT block (CGAX4R) numbered from
// 1 in the section's order, an *ELSET per region, NSET RIM, NSET TREAD_CENTRE and
// the element-based SURFACE INNER_LINER. The tread half width is not stored (it is
// an argument of the import). Throws cosim::Error if the file cannot be written.
void write_abaqus_cross_section(const CrossSection& section, const std::string& inp_path);

// Revolves the cross-section into hexahedra with the tread pattern: grooves remove
// tread elements, sipes split nodes, facets are tagged.
Mesh3D revolve(const CrossSection& section, const TreadPattern& pattern);

// A (deformed) cross-section state carried into 3D: node i of the mesh is node
// node_source[i] of the section at angle node_angle_rad[i], turned about the axis by
// that section node's twist (empty: none). This is Abaqus's *SYMMETRIC MODEL
// GENERATION + *SYMMETRIC RESULTS TRANSFER: the elements are total Lagrangian, so
// positions carry the stresses and rebar forces with them.
std::vector<Eigen::Vector3d> revolve_positions(const Mesh3D& mesh, const std::vector<Eigen::Vector2d>& section,
                                               const std::vector<double>& twist_rad);

}  // namespace tyre_fe
