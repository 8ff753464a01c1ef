#pragma once
// The rut a body leaves in the terrain's top surface (the tread indentation of
// the thesis, section 3.4, figure 3.3(d)). The particles are binned by (x, y)
// in square plan cells; a cell's surface is the height of its highest particle
// CENTRE (the centres' surface: half a spacing below the snow's top on an
// undisturbed lattice, nothing added for the particle's size); the rut is the
// lowering of that surface since a reference state, the run's step 0.
#include <cstddef>
#include <vector>

namespace snow_sph {

// Square plan cells over the terrain and each cell's top at the reference state.
struct RutGrid {
  double x0_m = 0.0, y0_m = 0.0;  // lower corner of cell (0, 0)
  double cell_m = 0.0;            // side of a cell
  std::size_t nx = 0, ny = 0;     // cell (i, j) is entry i + nx j
  std::vector<double> initial_top_z_m;  // per cell; NaN where no particle was

  double centre_x_m(std::size_t i) const { return x0_m + (static_cast<double>(i) + 0.5) * cell_m; }
  double centre_y_m(std::size_t j) const { return y0_m + (static_cast<double>(j) + 0.5) * cell_m; }
};

// Cells of side `cell_m` (one particle spacing) over the plan extent of the n
// particles, placed half a cell outside the outermost centres, so that each
// column of a regular lattice of that spacing (as the blocks are laid,
// scene.cpp) sits at a cell's centre: a particle moves half a spacing
// sideways before it counts in a neighbouring cell. Each cell's top is its
// highest particle centre now. Throws cosim::Error for no particles or cell_m <= 0.
RutGrid make_rut_grid(std::size_t n, const double* x, const double* y, const double* z, double cell_m);

// The top surface of the particles now against the grid's reference.
struct RutSurface {
  std::vector<double> top_z_m;     // per cell: highest centre now; NaN where none
  std::vector<double> lowering_m;  // per cell: reference top - top now; NaN where either is missing
  // The largest lowering over the cells that held particles then and hold
  // some now (0 if there are none); negative only if every such cell rose.
  double rut_depth_m = 0.0;
  std::size_t cells_compared = 0;
};

// Particles now outside the grid's cells are not counted (they have no
// reference top); cells emptied since the reference are left out of the rut.
RutSurface rut_surface(const RutGrid& grid, std::size_t n, const double* x, const double* y, const double* z);

}  // namespace snow_sph
