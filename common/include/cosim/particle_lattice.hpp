#pragma once
// How an SPH block's region is filled: whole cells of the particle spacing from
// the region's min corner, a particle at each cell's centre (snow_sph's
// build_model). When the spacing does not divide the region, the particles end
// short of its max face: the terrain's surface is then below the region's top,
// and the tyre's sinkage (coupler) and the plate's (snow_sph) are measured from
// the particles' top, not from the region's.
#include <cmath>

namespace cosim {

// Cells of `spacing_m` that fit between lo and hi (the 1e-6 of a cell keeps a
// division that is whole up to rounding whole).
inline long lattice_cells(double lo_m, double hi_m, double spacing_m) {
  return static_cast<long>(std::floor((hi_m - lo_m) / spacing_m + 1e-6));
}

// Where the particles' cells end: lo + cells * spacing.
inline double lattice_filled_max(double lo_m, double hi_m, double spacing_m) {
  return lo_m + static_cast<double>(lattice_cells(lo_m, hi_m, spacing_m)) * spacing_m;
}

}  // namespace cosim
