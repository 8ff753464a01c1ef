// The rut in the terrain's top surface (snow_sph/rut.hpp) on hand-made particle
// sets with a known dent: the slab of the thesis's tread indentation (section
// 3.4: 0.3 x 0.2 x 0.01 m, a tread pushed 8 mm in), laid as the scene builder
// lays blocks (cell-centred lattice, top of the block at z = 0).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "cosim/error.hpp"
#include "snow_sph/rut.hpp"

namespace {

struct Cloud {
  std::vector<double> x, y, z;
  void add(double px, double py, double pz) { x.push_back(px), y.push_back(py), z.push_back(pz); }
  std::size_t size() const { return x.size(); }
};

// Columns i < nx, j < ny of nz particles, centres at lo + (index + 0.5) dx,
// the block's top at z = 0. Columns inside the footprint [i0, i1) x [j0, j1)
// lose their top `dent_layers` particles (the snow pushed down and compacted).
struct Slab {
  double dx;
  int nx, ny, nz;
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0, dent_layers = 0;

  double x(int i) const { return (i - nx / 2 + 0.5) * dx; }
  double y(int j) const { return (j - ny / 2 + 0.5) * dx; }
  double z(int k) const { return (k - nz + 0.5) * dx; }
  bool in_dent(int i, int j) const { return i >= i0 && i < i1 && j >= j0 && j < j1; }

  Cloud particles(bool dented) const {
    Cloud c;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          if (!(dented && in_dent(i, j) && k >= nz - dent_layers)) c.add(x(i), y(j), z(k));
    return c;
  }
};

snow_sph::RutGrid grid_of(const Cloud& c, double cell) {
  return snow_sph::make_rut_grid(c.size(), c.x.data(), c.y.data(), c.z.data(), cell);
}

snow_sph::RutSurface rut_of(const snow_sph::RutGrid& g, const Cloud& c) {
  return snow_sph::rut_surface(g, c.size(), c.x.data(), c.y.data(), c.z.data());
}

TEST(Rut, TheGridHasOneCellPerLatticeColumnCentredOnIt) {
  const Slab slab{0.002, 150, 100, 5};
  const Cloud c = slab.particles(false);
  const snow_sph::RutGrid g = grid_of(c, slab.dx);
  ASSERT_EQ(g.nx, 150u);
  ASSERT_EQ(g.ny, 100u);
  // Centres to the rounding of the lattice's sums (a few 1e-17 m).
  EXPECT_NEAR(g.centre_x_m(0), slab.x(0), 1e-15);
  EXPECT_NEAR(g.centre_x_m(149), slab.x(149), 1e-15);
  EXPECT_NEAR(g.centre_y_m(99), slab.y(99), 1e-15);
  for (double top : g.initial_top_z_m) EXPECT_EQ(top, slab.z(4));  // the centres' surface: half a spacing down
}

TEST(Rut, ADentOfFourLayersGivesFourSpacingsExactly) {
  // Spacing 2^-9 m (1.95 mm): every height is a multiple of 2^-10 m below
  // 2^-6 m, exact in binary, and so is their difference: the rut depth must
  // equal the dent's 4 spacings (7.8 mm) to the last bit.
  Slab slab{1.0 / 512.0, 154, 102, 5};
  slab.i0 = 60, slab.i1 = 90, slab.j0 = 40, slab.j1 = 60, slab.dent_layers = 4;
  const snow_sph::RutGrid g = grid_of(slab.particles(false), slab.dx);
  Cloud now = slab.particles(true);
  // Sideways motion within half a cell leaves each particle in its cell.
  for (std::size_t p = 0; p < now.size(); ++p)
    now.x[p] += 0.4 * slab.dx * std::sin(0.7 * p), now.y[p] += 0.4 * slab.dx * std::cos(1.3 * p);
  const snow_sph::RutSurface rut = rut_of(g, now);
  EXPECT_EQ(rut.rut_depth_m, 4.0 * slab.dx);
  EXPECT_EQ(rut.cells_compared, g.nx * g.ny);
  const std::size_t inside = 70 + g.nx * 50, outside = 10 + g.nx * 10;
  EXPECT_EQ(rut.lowering_m[inside], 4.0 * slab.dx);
  EXPECT_EQ(rut.top_z_m[inside], slab.z(0));
  EXPECT_EQ(rut.lowering_m[outside], 0.0);
}

TEST(Rut, TheThesisSlabAtTwoMillimetresGivesTheEightMillimetreDent) {
  // 2 mm is not exact in binary: each height carries a few roundings of
  // centimetre-sized numbers (~1e-18 m each). 1e-15 m is far above that and
  // far below the error of a wrong cell or layer (a whole spacing, 2e-3 m).
  Slab slab{0.002, 150, 100, 5};
  slab.i0 = 55, slab.i1 = 95, slab.j0 = 35, slab.j1 = 65, slab.dent_layers = 4;
  const snow_sph::RutGrid g = grid_of(slab.particles(false), slab.dx);
  EXPECT_NEAR(rut_of(g, slab.particles(true)).rut_depth_m, 0.008, 1e-15);
}

TEST(Rut, OnlyTheTopParticleCountsAndHeaveIsNegativeLowering) {
  Slab slab{1.0 / 512.0, 20, 10, 5};
  const Cloud before = slab.particles(false);
  const snow_sph::RutGrid g = grid_of(before, slab.dx);
  Cloud now = before;
  now.z[0] -= 3.0 * slab.dx;  // a bottom particle pushed down under its column: the top did not move
  now.add(slab.x(5), slab.y(5), slab.z(4) + slab.dx);  // heave: one particle above the top
  const snow_sph::RutSurface rut = rut_of(g, now);
  EXPECT_EQ(rut.lowering_m[5 + g.nx * 5], -slab.dx);
  EXPECT_EQ(rut.rut_depth_m, 0.0);
}

TEST(Rut, EmptiedCellsAndParticlesOutsideTheGridAreLeftOut) {
  Slab slab{1.0 / 512.0, 20, 10, 5};
  const snow_sph::RutGrid g = grid_of(slab.particles(false), slab.dx);
  Cloud now;
  const Cloud before = slab.particles(false);
  for (std::size_t p = 0; p < before.size(); ++p)
    if (!(before.x[p] == slab.x(3) && before.y[p] == slab.y(2)))  // column (3, 2) emptied
      now.add(before.x[p], before.y[p], before.z[p]);
  now.add(slab.x(19) + slab.dx, slab.y(0), -0.5);  // beyond the grid, far below: no cell, no rut
  const snow_sph::RutSurface rut = rut_of(g, now);
  EXPECT_EQ(rut.cells_compared, g.nx * g.ny - 1);
  EXPECT_TRUE(std::isnan(rut.lowering_m[3 + g.nx * 2]));
  EXPECT_TRUE(std::isnan(rut.top_z_m[3 + g.nx * 2]));
  EXPECT_EQ(rut.rut_depth_m, 0.0);
}

TEST(Rut, NoParticlesOrNoCellSizeIsRefused) {
  const double v = 0.0;
  EXPECT_THROW(snow_sph::make_rut_grid(0, &v, &v, &v, 0.002), cosim::Error);
  EXPECT_THROW(snow_sph::make_rut_grid(1, &v, &v, &v, 0.0), cosim::Error);
}

}  // namespace
