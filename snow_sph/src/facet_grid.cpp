// The binning stage of the surface contact (facet_grid.hpp).
#include "snow_sph/facet_grid.hpp"

#include <algorithm>
#include <cmath>

#include "cosim/quad_facet.hpp"

namespace snow_sph {

using V3 = Eigen::Vector3d;

FacetGrid bin_facets(const ContactSurface& s, double reach) {
  FacetGrid g;
  const std::size_t nf = s.facet_count();
  std::vector<double> box(6 * nf);
  double extent = 0.0;
  for (int a = 0; a < 3; ++a) g.lo[a] = 1e300, g.hi[a] = -1e300;
  for (std::size_t f = 0; f < nf; ++f) {
    double* b = &box[6 * f];
    for (int a = 0; a < 3; ++a) b[a] = 1e300, b[3 + a] = -1e300;
    for (int q = 0; q < 4; ++q) {
      const std::uint32_t n = s.facet_nodes[4 * f + q];
      const double p[3] = {s.x[n], s.y[n], s.z[n]};
      for (int a = 0; a < 3; ++a) b[a] = std::min(b[a], p[a] - reach), b[3 + a] = std::max(b[3 + a], p[a] + reach);
    }
    for (int a = 0; a < 3; ++a) {
      extent = std::max(extent, b[3 + a] - b[a]);
      g.lo[a] = std::min(g.lo[a], b[a]), g.hi[a] = std::max(g.hi[a], b[3 + a]);
    }
  }
  // About one grown facet per cell, at most ~4 million cells.
  g.cell = std::max(extent, 1e-6);
  while (true) {
    long total = 1;
    for (int a = 0; a < 3; ++a) g.dims[a] = std::max(1, static_cast<int>(std::ceil((g.hi[a] - g.lo[a]) / g.cell)));
    total = static_cast<long>(g.dims[0]) * g.dims[1] * g.dims[2];
    if (total <= 4000000) break;
    g.cell *= 1.5;
  }
  const std::size_t cells = static_cast<std::size_t>(g.dims[0]) * g.dims[1] * g.dims[2];
  std::vector<std::uint32_t> count(cells + 1, 0);
  auto each_cell = [&](std::size_t f, auto&& visit) {
    int c0[3], c1[3];
    for (int a = 0; a < 3; ++a) {
      c0[a] = std::clamp(static_cast<int>((box[6 * f + a] - g.lo[a]) / g.cell), 0, g.dims[a] - 1);
      c1[a] = std::clamp(static_cast<int>((box[6 * f + 3 + a] - g.lo[a]) / g.cell), 0, g.dims[a] - 1);
    }
    for (int k = c0[2]; k <= c1[2]; ++k)
      for (int j = c0[1]; j <= c1[1]; ++j)
        for (int i = c0[0]; i <= c1[0]; ++i) visit(g.index(i, j, k));
  };
  // A closed slit's faces take no particle (ContactSurface::closed_slit): not binned, never visited.
  auto takes_particles = [&](std::size_t f) { return s.closed_slit.empty() || !s.closed_slit[f]; };
  for (std::size_t f = 0; f < nf; ++f)
    if (takes_particles(f)) each_cell(f, [&](int c) { ++count[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
  g.begin = count;
  g.entries.resize(count[cells]);
  for (std::size_t f = 0; f < nf; ++f)
    if (takes_particles(f)) each_cell(f, [&](int c) { g.entries[count[c]++] = static_cast<std::uint32_t>(f); });
  return g;
}

V3 facet_area_vector(const ContactSurface& s, std::size_t f) {
  const std::uint32_t* q = &s.facet_nodes[4 * f];
  auto node = [&](std::uint32_t n) { return V3(s.x[n], s.y[n], s.z[n]); };
  return cosim::quad_area_vector(node(q[0]), node(q[1]), node(q[2]), node(q[3]));
}

}  // namespace snow_sph
