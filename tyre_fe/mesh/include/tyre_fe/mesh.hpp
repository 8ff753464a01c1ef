#pragma once
// Tyre meshes: the 2D axisymmetric cross-section and the 3D model revolved from it.
//
// Axes (ISO 8855, wheel frame): x forward, y left (the wheel's spin axis), z up;
// the wheel centre is the origin. A cross-section lives in the (r, y) half plane,
// r >= 0 the distance from the spin axis. Revolving a cross-section point (r, y)
// to the angle theta (about +y, theta = 0 at the top, pi at the road) gives
//   x = r sin(theta),  y = y,  z = r cos(theta).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cosim/facet_tag.hpp"

namespace tyre_fe {

// Tyre regions of thesis figure 5.3 / Table 5.4; one material each.
enum class Region : std::uint8_t {
  tread,
  sidewall,
  inner_liner,
  ply,
  belt_1,
  belt_2,
  bead,
  filler,
  rim_strip,
  count
};
constexpr int kRegionCount = static_cast<int>(Region::count);
// "tread", "sidewall", "inner_liner", "ply", "belt_1", "belt_2", "bead", "filler", "rim_strip"
const char* region_name(Region r);
// Throws cosim::Error for an unknown name.
Region region_from_name(const std::string& name);

// Tags of 3D boundary facets: the project's one facet-tag enum
// (cosim/facet_tag.hpp), which the wire carries and the coupler chooses friction by.
using SurfaceTag = cosim::FacetTag;

// A rebar layer smeared into the host elements of one region (Abaqus *REBAR LAYER):
// bars of cross-section `area_m2` every `spacing_m`, at `angle_rad` measured in the
// layer's surface from the meridional direction towards the circumferential one
// (0: radial cords; +-66.7 deg: belts, thesis Table 5.3).
struct RebarLayer {
  double area_m2 = 0.0;
  double spacing_m = 0.0;
  double angle_rad = 0.0;
  double youngs_modulus_Pa = 0.0;
  double density_kg_per_m3 = 0.0;
};

// 2D axisymmetric mesh of 4-node quadrilaterals (counter-clockwise in the (r, y)
// plane, i.e. positive area with r as the first and y as the second coordinate).
struct CrossSection {
  std::vector<Eigen::Vector2d> nodes;  // (r, y) [m], reference (uninflated) positions
  std::vector<std::array<int, 4>> quads;
  std::vector<Region> quad_region;
  // Per quad: unit meridional tangent of the layer through it (r, y components),
  // the direction a rebar at angle 0 runs in; (0, 0) where the region has no rebar.
  // It points along the contour from the y < 0 bead towards the y > 0 one (+y on
  // the crown), so that a belt angle has the same sense across the whole belt.
  std::vector<Eigen::Vector2d> quad_layer_tangent;
  // Per quad: thickness of the layer the quad belongs to [m] (rebar volume
  // fraction = area / (spacing * thickness)).
  std::vector<double> quad_layer_thickness_m;
  // Edges loaded by the inflation pressure: (quad, local edge k = nodes k -> k+1).
  std::vector<std::array<int, 2>> inner_liner_edges;
  // Nodes held by the rim (bead seat and rim flange contact).
  std::vector<int> rim_nodes;
  // Node on the outer tread surface at y = 0 (the tread centre).
  int tread_centre_node = -1;
  // Tread surface half width [m] (where the tread top ends and the shoulder starts).
  double tread_half_width_m = 0.0;
};

// Adds every node of the region's quads to the rim nodes (sorted, no repeats): the
// region then moves rigidly with the rim (used for the steel bead bundle).
void tie_region_to_rim(CrossSection& section, Region region);

// 3D mesh of 8-node hexahedra revolved from a cross-section (with a tread pattern).
// Node order of a hex: the quad's nodes in reverse order (q0, q3, q2, q1) at angle
// theta_j, then the same at theta_j+1. A counter-clockwise (r, y) quad has its
// right-hand normal along -e_theta, so reversing it makes face 0-3 point towards
// face 4-7: the hex has positive volume (VTK_HEXAHEDRON / Abaqus C3D8 order, see
// hex8 element). Hex faces and quad edges: face (0,1,5,4) is quad edge 3,
// (1,2,6,5) edge 2, (2,3,7,6) edge 1, (3,0,4,7) edge 0.
struct Mesh3D {
  std::vector<Eigen::Vector3d> nodes;  // reference (uninflated) positions
  // Each 3D node comes from cross-section node `node_source[i]` at angle `node_angle_rad[i]`;
  // used to carry a deformed (inflated) cross-section state into 3D.
  std::vector<int> node_source;
  std::vector<double> node_angle_rad;
  std::vector<std::array<int, 8>> hexes;
  std::vector<Region> hex_region;
  std::vector<int> hex_source_quad;    // the cross-section quad it was revolved from
  std::vector<double> hex_angle_rad;   // angle of its centre
  struct Facet {
    std::array<int, 4> nodes;  // ordered so that the right-hand normal points out of the body
    SurfaceTag tag;
    int hex;
  };
  std::vector<Facet> facets;  // tagged boundary facets
  std::vector<int> rim_nodes;
  // Sipes (block_sipes only, else 0): the pattern's nominal width, which the mesh
  // does not resolve (a sipe is a zero-width slit), and the depth of the slits as
  // meshed (the nominal depth rounded to the nearest element boundary).
  double sipe_width_m = 0.0;
  double sipe_depth_m = 0.0;
};

}  // namespace tyre_fe
