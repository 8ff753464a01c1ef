// Quad facet centroids, normals and areas; see facet_geometry.hpp.
#include "coupler/facet_geometry.hpp"

#include <Eigen/Core>
#include <string>

#include "cosim/error.hpp"
#include "cosim/quad_facet.hpp"

namespace coupler {

FacetGeometry quad_facet_geometry(const std::vector<double>& x_m, const std::vector<double>& y_m,
                                  const std::vector<double>& z_m, const std::vector<std::uint32_t>& facet_nodes) {
  const std::size_t n_nodes = x_m.size();
  if (y_m.size() != n_nodes || z_m.size() != n_nodes)
    throw cosim::Error("facet geometry: x, y, z node arrays differ in length");
  if (facet_nodes.size() % 4 != 0)
    throw cosim::Error("facet geometry: facet_nodes has " + std::to_string(facet_nodes.size()) +
                       " entries, not 4 per quad facet");
  const std::size_t n = facet_nodes.size() / 4;
  FacetGeometry g;
  for (auto* v : {&g.centroid_x_m, &g.centroid_y_m, &g.centroid_z_m, &g.normal_x, &g.normal_y, &g.normal_z, &g.area_m2})
    v->resize(n);
  for (std::size_t f = 0; f < n; ++f) {
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t i = facet_nodes[4 * f + k];
      if (i >= n_nodes)
        throw cosim::Error("facet geometry: facet " + std::to_string(f) + " refers to node " + std::to_string(i) +
                           " of " + std::to_string(n_nodes));
      p[k] = {x_m[i], y_m[i], z_m[i]};
    }
    const cosim::QuadFacet q = cosim::quad_facet(p[0], p[1], p[2], p[3]);
    if (!(q.area > 0.0)) throw cosim::Error("facet geometry: facet " + std::to_string(f) + " has zero area");
    g.centroid_x_m[f] = q.centroid.x(), g.centroid_y_m[f] = q.centroid.y(), g.centroid_z_m[f] = q.centroid.z();
    g.normal_x[f] = q.normal.x(), g.normal_y[f] = q.normal.y(), g.normal_z[f] = q.normal.z();
    g.area_m2[f] = q.area;
  }
  return g;
}

}  // namespace coupler
