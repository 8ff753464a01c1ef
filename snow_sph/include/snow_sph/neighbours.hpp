#pragma once
// Neighbour search: a uniform cell list feeding an index-based (CSR) Verlet
// list with a skin, rebuilt only when a particle has moved more than half the
// skin. Tested against a brute-force O(n^2) search (tests/snow_sph/test_neighbours.cpp).
#include <cstdint>
#include <vector>

namespace snow_sph {

struct NeighbourList {
  std::vector<std::uint32_t> offsets;  // size n_query + 1
  std::vector<std::uint32_t> index;    // neighbour j of query i: index[offsets[i] .. offsets[i+1])
  double radius = 0.0;                 // list radius (support + skin)
  std::size_t pairs() const { return index.size(); }
};

// Builds the list of all points j in [0, n_all) within `radius` of each query
// point i in [0, n_query) (queries are the first n_query points), excluding i.
void build_neighbour_list(const double* x, const double* y, const double* z, std::size_t n_query,
                          std::size_t n_all, double radius, NeighbourList& list);

// Order that sorts points by cell (for memory locality), cell size `cell`.
std::vector<std::uint32_t> cell_order(const double* x, const double* y, const double* z,
                                      std::size_t n, double cell);

}  // namespace snow_sph
