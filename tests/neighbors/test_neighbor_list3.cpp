// The neighbour search in 3D (neighbors/neighbor_list.hpp instantiated for D = 3): the pair list
// against a brute-force search with minimum images, in a bounded box and with every axis
// periodic, particles straying outside a bounded box included; the order of each particle's
// neighbours the same whatever the thread count; the smallest pair distance.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <random>
#include <vector>

#include "particula/neighbors/neighbor_list.hpp"

using namespace particula;

namespace {

/// n random particles in the domain, a few of them up to 0.3 h outside a bounded one.
std::vector<Vec3> scatter(const Domain3& d, int n, real h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<real> u(0, 1);
  std::vector<Vec3> x(n);
  for (int k = 0; k < n; ++k) {
    const Vec3 L = d.size();
    x[k] = d.lo + Vec3{u(rng) * L.x, u(rng) * L.y, u(rng) * L.z};
    if (k % 50 == 0 && !d.periodic_x) x[k].x = d.lo.x - 0.3 * h * u(rng);  // strayed out
  }
  return x;
}

/// The neighbours of every particle by brute force, sorted.
std::vector<std::vector<std::uint32_t>> brute_force(const std::vector<Vec3>& x, const Domain3& d, real h) {
  std::vector<std::vector<std::uint32_t>> nb(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j < x.size(); ++j)
      if (i != j && norm(d.separation(x[i], x[j])) < h) nb[i].push_back(static_cast<std::uint32_t>(j));
  return nb;
}

void expect_list_is_brute_force(const Domain3& d, real h) {
  const std::vector<Vec3> x = scatter(d, 3000, h, 11);
  CellGrid3 grid;
  grid.setup(d, h, 0.5 * h);
  NeighborList list;
  build_neighbor_list(x, d, Wendland<3>(h), grid, list);
  const auto exact = brute_force(x, d, h);
  real dmin = 1e300;
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    std::vector<std::uint32_t> row(list.j.begin() + list.start[i], list.j.begin() + list.start[i + 1]);
    for (const std::uint32_t j : row) dmin = std::min(dmin, norm(d.separation(x[i], x[j])));
    std::sort(row.begin(), row.end());
    EXPECT_EQ(row, exact[i]) << "particle " << i;
    pairs += row.size();
  }
  EXPECT_GT(pairs, 20 * x.size());  // about 33 neighbours each at this density
  EXPECT_DOUBLE_EQ(list.min_distance, dmin);
}

}  // namespace

TEST(NeighborList3, BoundedBoxMatchesBruteForce) {
  Domain3 d;
  d.lo = {0, 0, 0};
  d.hi = {1.0, 0.8, 0.6};
  expect_list_is_brute_force(d, 0.15);
}

TEST(NeighborList3, PeriodicBoxMatchesBruteForce) {
  Domain3 d;
  d.lo = {-0.5, 0, 0.2};
  d.hi = {0.5, 0.8, 0.8};
  d.periodic_x = d.periodic_y = d.periodic_z = true;
  expect_list_is_brute_force(d, 0.15);
  // and a wrapped position stays in the box
  const Vec3 w = d.wrap({0.7, -0.1, 0.8});
  EXPECT_NEAR(w.x, -0.3, 1e-15);
  EXPECT_NEAR(w.y, 0.7, 1e-15);
  EXPECT_NEAR(w.z, 0.2, 1e-15);
}

TEST(NeighborList3, OrderIsIndependentOfTheThreadCount) {
  Domain3 d;
  d.lo = {0, 0, 0};
  d.hi = {1.0, 0.8, 0.6};
  d.periodic_y = true;
  const std::vector<Vec3> x = scatter(d, 4000, 0.12, 5);
  NeighborList one, two;
  CellGrid3 grid;
  grid.setup(d, 0.12, 0.1);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  build_neighbor_list(x, d, Wendland<3>(0.12), grid, one);
  omp_set_num_threads(3);
  build_neighbor_list(x, d, Wendland<3>(0.12), grid, two);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.start, two.start);
  EXPECT_EQ(one.j, two.j);
}
