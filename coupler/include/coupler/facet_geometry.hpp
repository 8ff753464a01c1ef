#pragma once
// Geometry of the tyre's quad surface facets from current node positions, and
// the facet pressure force as a vector. Inputs follow SurfaceMesh /
// SurfaceKinematics: per-node coordinate arrays and 4 node indices per facet,
// ordered so that the right-hand normal points out of the tyre (tyre_fe::Mesh3D).
#include <cstdint>
#include <vector>

namespace coupler {

// Per facet: centroid, unit outward normal, area (structure of arrays).
struct FacetGeometry {
  std::vector<double> centroid_x_m, centroid_y_m, centroid_z_m;
  std::vector<double> normal_x, normal_y, normal_z;
  std::vector<double> area_m2;
};

// Centroid = mean of the 4 nodes; vector area = (x2 - x0) x (x3 - x1) / 2, exact
// for a planar quad (the bilinear quad's mean normal otherwise); cosim::quad_facet
// per facet. Throws
// cosim::Error on size mismatches, out-of-range node indices or a zero-area facet.
FacetGeometry quad_facet_geometry(const std::vector<double>& x_m, const std::vector<double>& y_m,
                                  const std::vector<double>& z_m, const std::vector<std::uint32_t>& facet_nodes);

}  // namespace coupler
