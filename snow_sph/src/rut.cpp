#include "snow_sph/rut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cosim/error.hpp"

namespace snow_sph {
namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

// The highest particle centre per cell (NaN where no particle is); particles
// outside the grid are skipped.
std::vector<double> top_per_cell(const RutGrid& g, std::size_t n, const double* x, const double* y,
                                 const double* z) {
  std::vector<double> top(g.nx * g.ny, kNone);
  for (std::size_t p = 0; p < n; ++p) {
    const double fi = std::floor((x[p] - g.x0_m) / g.cell_m), fj = std::floor((y[p] - g.y0_m) / g.cell_m);
    if (!(fi >= 0 && fj >= 0 && fi < static_cast<double>(g.nx) && fj < static_cast<double>(g.ny))) continue;
    double& t = top[static_cast<std::size_t>(fi) + g.nx * static_cast<std::size_t>(fj)];
    if (std::isnan(t) || z[p] > t) t = z[p];
  }
  return top;
}

}  // namespace

RutGrid make_rut_grid(std::size_t n, const double* x, const double* y, const double* z, double cell_m) {
  if (n == 0) throw cosim::Error("rut grid: no particles");
  if (!(cell_m > 0)) throw cosim::Error("rut grid: the cell side must be > 0");
  const auto [x_lo, x_hi] = std::minmax_element(x, x + n);
  const auto [y_lo, y_hi] = std::minmax_element(y, y + n);
  RutGrid g;
  g.cell_m = cell_m;
  g.x0_m = *x_lo - 0.5 * cell_m, g.y0_m = *y_lo - 0.5 * cell_m;
  // The outermost centres lie half a cell inside the last cells' far side.
  g.nx = static_cast<std::size_t>(std::floor((*x_hi - g.x0_m) / cell_m)) + 1;
  g.ny = static_cast<std::size_t>(std::floor((*y_hi - g.y0_m) / cell_m)) + 1;
  g.initial_top_z_m = top_per_cell(g, n, x, y, z);
  return g;
}

RutSurface rut_surface(const RutGrid& g, std::size_t n, const double* x, const double* y, const double* z) {
  RutSurface r;
  r.top_z_m = top_per_cell(g, n, x, y, z);
  r.lowering_m.assign(r.top_z_m.size(), kNone);
  double deepest = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < r.top_z_m.size(); ++c) {
    if (std::isnan(r.top_z_m[c]) || std::isnan(g.initial_top_z_m[c])) continue;
    r.lowering_m[c] = g.initial_top_z_m[c] - r.top_z_m[c];
    deepest = std::max(deepest, r.lowering_m[c]);
    ++r.cells_compared;
  }
  r.rut_depth_m = r.cells_compared ? deepest : 0.0;
  return r;
}

}  // namespace snow_sph
