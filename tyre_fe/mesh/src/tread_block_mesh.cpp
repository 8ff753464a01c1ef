#include "tyre_fe/tread_block_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace tyre_fe {
namespace {

// The grid lines of [a, b]: the breaks inside it, each interval cut into equal
// pieces no longer than h.
std::vector<double> grid_lines(double a, double b, std::vector<double> breaks, double h) {
  breaks.push_back(a), breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> lines{a};
  for (std::size_t k = 1; k < breaks.size(); ++k) {
    const double lo = breaks[k - 1], hi = breaks[k];
    if (hi - lo < 1e-12) continue;
    const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) / h - 1e-9)));
    for (int i = 1; i <= n; ++i) lines.push_back(lo + (hi - lo) * i / n);
  }
  return lines;
}

}  // namespace

Mesh3D make_tread_block_mesh(const TreadBlockGeometry& g, double face_z_m) {
  const double hx = 0.5 * g.length_x_m, hy = 0.5 * g.width_y_m, h = g.element_size_m;
  std::vector<double> edges;
  for (double c : g.groove_x_m) edges.push_back(c - 0.5 * g.groove_width_m), edges.push_back(c + 0.5 * g.groove_width_m);
  const auto X = grid_lines(-hx, hx, edges, h), Y = grid_lines(-hy, hy, {}, h);
  const auto Z = grid_lines(face_z_m, face_z_m + g.groove_depth_m + g.base_thickness_m,
                            {face_z_m + g.groove_depth_m}, h);
  const int nx = static_cast<int>(X.size()) - 1, ny = static_cast<int>(Y.size()) - 1,
            nz = static_cast<int>(Z.size()) - 1;
  int rib_layers = 0;  // cell layers below the groove floor
  while (rib_layers < nz && Z[rib_layers + 1] <= face_z_m + g.groove_depth_m + 1e-12) ++rib_layers;
  auto in_groove = [&](int i) {
    const double xc = 0.5 * (X[i] + X[i + 1]);
    for (double c : g.groove_x_m)
      if (std::fabs(xc - c) < 0.5 * g.groove_width_m) return true;
    return false;
  };
  auto solid = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz && (k >= rib_layers || !in_groove(i));
  };
  Mesh3D m;
  std::vector<int> node_of((nx + 1) * (ny + 1) * (nz + 1), -1);
  auto node = [&](int i, int j, int k) {
    int& id = node_of[(k * (ny + 1) + j) * (nx + 1) + i];
    if (id < 0) {
      id = static_cast<int>(m.nodes.size());
      m.nodes.emplace_back(X[i], Y[j], Z[k]);
      m.node_source.push_back(-1), m.node_angle_rad.push_back(0.0);
      if (k == nz) m.rim_nodes.push_back(id);
    }
    return id;
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!solid(i, j, k)) continue;
        // VTK_HEXAHEDRON order: the face at k counter-clockwise seen from +z, then the face at k + 1.
        const std::array<int, 8> c{node(i, j, k),         node(i + 1, j, k),     node(i + 1, j + 1, k),
                                   node(i, j + 1, k),     node(i, j, k + 1),     node(i + 1, j, k + 1),
                                   node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        const int e = static_cast<int>(m.hexes.size());
        m.hexes.push_back(c);
        m.hex_region.push_back(Region::tread);
        m.hex_source_quad.push_back(-1);
        m.hex_angle_rad.push_back(0.0);
        // Boundary faces, ordered so that the right-hand normal points out of the block.
        auto face = [&](bool boundary, std::array<int, 4> q, SurfaceTag tag) {
          if (boundary) m.facets.push_back({{c[q[0]], c[q[1]], c[q[2]], c[q[3]]}, tag, e});
        };
        face(!solid(i, j, k - 1), {0, 3, 2, 1}, k == 0 ? SurfaceTag::tread_top : SurfaceTag::groove_bottom);
        face(k == nz - 1, {4, 5, 6, 7}, SurfaceTag::rim_contact);
        face(!solid(i - 1, j, k), {0, 4, 7, 3}, i == 0 ? SurfaceTag::shoulder : SurfaceTag::groove_wall);
        face(!solid(i + 1, j, k), {1, 2, 6, 5}, i == nx - 1 ? SurfaceTag::shoulder : SurfaceTag::groove_wall);
        face(!g.slice_in_y && j == 0, {0, 1, 5, 4}, SurfaceTag::other);
        face(!g.slice_in_y && j == ny - 1, {3, 7, 6, 2}, SurfaceTag::other);
      }
  std::sort(m.rim_nodes.begin(), m.rim_nodes.end());
  return m;
}

}  // namespace tyre_fe
