// Cell-list neighbour search against a brute-force O(n^2) search.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "snow_sph/neighbours.hpp"

TEST(Neighbours, MatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 0.1);
  const std::size_t n_all = 3000, n_query = 2000;
  std::vector<double> x(n_all), y(n_all), z(n_all);
  for (std::size_t i = 0; i < n_all; ++i) x[i] = u(rng), y[i] = 0.5 * u(rng), z[i] = 2 * u(rng);
  const double radius = 0.012;
  snow_sph::NeighbourList list;
  snow_sph::build_neighbour_list(x.data(), y.data(), z.data(), n_query, n_all, radius, list);
  std::size_t total = 0;
  for (std::size_t i = 0; i < n_query; ++i) {
    std::vector<std::uint32_t> expected;
    for (std::size_t j = 0; j < n_all; ++j) {
      const double dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
      if (j != i && dx * dx + dy * dy + dz * dz < radius * radius) expected.push_back(j);
    }
    std::vector<std::uint32_t> got(list.index.begin() + list.offsets[i], list.index.begin() + list.offsets[i + 1]);
    ASSERT_EQ(got, expected) << "query " << i;
    total += got.size();
  }
  EXPECT_GT(total, n_query);  // the test exercises real neighbourhoods
}

TEST(Neighbours, CellOrderIsAPermutation) {
  std::vector<double> x{0.32, 0.11, 0.21, 0.0}, y(4, 0.0), z(4, 0.0);
  auto order = snow_sph::cell_order(x.data(), y.data(), z.data(), 4, 0.1);
  std::set<std::uint32_t> s(order.begin(), order.end());
  EXPECT_EQ(s.size(), 4u);
  EXPECT_EQ(order.front(), 3u);
  EXPECT_EQ(order.back(), 0u);
}
