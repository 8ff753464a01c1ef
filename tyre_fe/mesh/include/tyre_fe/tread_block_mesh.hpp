#pragma once
// The mesh of a tread block (thesis 3.4; tread_block.hpp runs it): ribs over a
// solid base, hexahedra on a grid whose lines follow the grooves' edges.
#include <vector>

#include "tyre_fe/mesh.hpp"

namespace tyre_fe {

struct TreadBlockGeometry {
  double length_x_m = 0.0, width_y_m = 0.0;
  double base_thickness_m = 0.0, groove_depth_m = 0.0;
  std::vector<double> groove_x_m;  // groove centres; grooves run along y
  double groove_width_m = 0.0;
  double element_size_m = 0.0;
  bool slice_in_y = false;  // no facets on the faces normal to y
};

// Hexahedra on a grid whose x lines include every groove edge; the ribs' faces
// at z = face_z_m, the top at face_z_m + groove_depth + base. Facet tags: the
// ribs' faces tread_top, the grooves' walls groove_wall and floors
// groove_bottom, the x ends shoulder, the y sides other (none if slice_in_y),
// the top rim_contact (held by the reference node, no contact). rim_nodes: the
// top face's nodes.
Mesh3D make_tread_block_mesh(const TreadBlockGeometry& g, double face_z_m);

}  // namespace tyre_fe
