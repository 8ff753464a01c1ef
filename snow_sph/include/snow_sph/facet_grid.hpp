#pragma once
// The binning stage of the surface contact: the coupled surface's facets in a
// uniform grid (CSR: cell -> facets) over their bounding boxes grown by the
// contact's reach, so that each particle tests only the facets of its cell.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

// Facets binned in a uniform grid over their bounding boxes grown by the reach.
struct FacetGrid {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, cell = 1.0;
  int dims[3] = {1, 1, 1};
  std::vector<std::uint32_t> begin, entries;  // CSR: cell -> facets

  int index(int i, int j, int k) const { return (k * dims[1] + j) * dims[0] + i; }
  bool cell_of(const Eigen::Vector3d& p, int c[3]) const {
    for (int a = 0; a < 3; ++a) {
      if (p[a] < lo[a] || p[a] > hi[a]) return false;
      c[a] = std::min(dims[a] - 1, static_cast<int>((p[a] - lo[a]) / cell));
    }
    return true;
  }
};

FacetGrid bin_facets(const ContactSurface& s, double reach);

// Facet f's area vector (cosim::quad_area_vector): its length is the area, exact
// for a planar quad, and it points along the outward normal.
Eigen::Vector3d facet_area_vector(const ContactSurface& s, std::size_t f);

}  // namespace snow_sph
