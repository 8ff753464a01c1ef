#include "snow_sph/neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cosim/parallel.hpp"

namespace snow_sph {
namespace {

struct Grid {
  double x0, y0, z0, inv_cell;
  long nx, ny, nz;
  long cell_of(double x, double y, double z) const {
    const long i = std::clamp(static_cast<long>((x - x0) * inv_cell), 0L, nx - 1);
    const long j = std::clamp(static_cast<long>((y - y0) * inv_cell), 0L, ny - 1);
    const long k = std::clamp(static_cast<long>((z - z0) * inv_cell), 0L, nz - 1);
    return (k * ny + j) * nx + i;
  }
};

Grid make_grid(const double* x, const double* y, const double* z, std::size_t n, double cell) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < n; ++i) {
    lo[0] = std::min(lo[0], x[i]), hi[0] = std::max(hi[0], x[i]);
    lo[1] = std::min(lo[1], y[i]), hi[1] = std::max(hi[1], y[i]);
    lo[2] = std::min(lo[2], z[i]), hi[2] = std::max(hi[2], z[i]);
  }
  Grid g;
  g.x0 = lo[0], g.y0 = lo[1], g.z0 = lo[2];
  g.inv_cell = 1.0 / cell;
  g.nx = std::max(1L, static_cast<long>((hi[0] - lo[0]) / cell) + 1);
  g.ny = std::max(1L, static_cast<long>((hi[1] - lo[1]) / cell) + 1);
  g.nz = std::max(1L, static_cast<long>((hi[2] - lo[2]) / cell) + 1);
  return g;
}

}  // namespace

std::vector<std::uint32_t> cell_order(const double* x, const double* y, const double* z,
                                      std::size_t n, double cell) {
  std::vector<std::uint32_t> order(n);
  if (n == 0) return order;
  const Grid g = make_grid(x, y, z, n, cell);
  std::vector<long> key(n);
  for (std::size_t i = 0; i < n; ++i) key[i] = g.cell_of(x[i], y[i], z[i]);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return key[a] < key[b]; });
  return order;
}

void build_neighbour_list(const double* x, const double* y, const double* z, std::size_t n_query,
                          std::size_t n_all, double radius, NeighbourList& list) {
  list.radius = radius;
  list.offsets.assign(n_query + 1, 0);
  list.index.clear();
  if (n_all == 0) return;
  const Grid g = make_grid(x, y, z, n_all, radius);
  const long n_cells = g.nx * g.ny * g.nz;
  // Counting sort of all points into cells.
  std::vector<std::uint32_t> cell_start(n_cells + 1, 0), sorted(n_all);
  std::vector<long> cell_of(n_all);
  for (std::size_t i = 0; i < n_all; ++i) {
    cell_of[i] = g.cell_of(x[i], y[i], z[i]);
    ++cell_start[cell_of[i] + 1];
  }
  for (long c = 0; c < n_cells; ++c) cell_start[c + 1] += cell_start[c];
  {
    std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n_all; ++i) sorted[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  }
  const double r2 = radius * radius;
  // Two passes (count, then fill) so each query writes only its own slice.
  auto visit = [&](std::size_t i, auto&& emit) {
    const long c = cell_of[i];
    const long ci = c % g.nx, cj = (c / g.nx) % g.ny, ck = c / (g.nx * g.ny);
    for (long dk = -1; dk <= 1; ++dk) {
      const long k = ck + dk;
      if (k < 0 || k >= g.nz) continue;
      for (long dj = -1; dj <= 1; ++dj) {
        const long j = cj + dj;
        if (j < 0 || j >= g.ny) continue;
        for (long di = -1; di <= 1; ++di) {
          const long ii = ci + di;
          if (ii < 0 || ii >= g.nx) continue;
          const long cell = (k * g.ny + j) * g.nx + ii;
          for (std::uint32_t s = cell_start[cell]; s < cell_start[cell + 1]; ++s) {
            const std::uint32_t p = sorted[s];
            if (p == i) continue;
            const double dx = x[i] - x[p], dy = y[i] - y[p], dz = z[i] - z[p];
            if (dx * dx + dy * dy + dz * dz < r2) emit(p);
          }
        }
      }
    }
  };
  std::vector<std::uint32_t> counts(n_query);
  cosim::parallel_for("neighbours.count", n_query, [&](std::size_t i) {
    std::uint32_t c = 0;
    visit(i, [&](std::uint32_t) { ++c; });
    counts[i] = c;
  });
  for (std::size_t i = 0; i < n_query; ++i) list.offsets[i + 1] = list.offsets[i] + counts[i];
  list.index.resize(list.offsets[n_query]);
  cosim::parallel_for("neighbours.fill", n_query, [&](std::size_t i) {
    std::uint32_t w = list.offsets[i];
    visit(i, [&](std::uint32_t p) { list.index[w++] = p; });
    // Sorted neighbours: deterministic order and better locality.
    std::sort(list.index.begin() + list.offsets[i], list.index.begin() + list.offsets[i + 1]);
  });
}

}  // namespace snow_sph
