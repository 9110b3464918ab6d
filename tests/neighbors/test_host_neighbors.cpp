// The host's neighbours at a set of positions (HostNeighbors, neighbors/neighbor_list.hpp): the
// rows of a neighbour list built at them and the visit of a grid binned at them give the same
// neighbours in the same order, so that what reads them (the load band's Voronoi cells) gets the
// same sums from either.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "particula/neighbors/neighbor_list.hpp"
#include "particula/sph/kernel.hpp"

using namespace particula;

namespace {

std::vector<std::vector<std::uint32_t>> visited(const HostNeighbors& nbrs, const std::vector<Vec2>& x) {
  std::vector<std::vector<std::uint32_t>> out(x.size());
  for (std::uint32_t i = 0; i < x.size(); ++i) nbrs.visit(x.data(), i, [&](std::uint32_t j) { out[i].push_back(j); });
  return out;
}

}  // namespace

TEST(HostNeighbors, ListRowsAndGridVisitGiveTheSameNeighboursInTheSameOrder) {
  for (const bool periodic : {false, true}) {
    Domain dom;
    dom.lo = {0, 0};
    dom.hi = {1.0, 0.6};
    dom.periodic_x = periodic;
    const real h = 0.07;
    std::mt19937 rng(11);
    std::uniform_real_distribution<real> ux(0, 1.0), uy(0, 0.6);
    std::vector<Vec2> x(800);
    for (Vec2& p : x) p = {ux(rng), uy(rng)};
    CellGrid list_grid, grid;
    list_grid.setup(dom, h);
    grid.setup(dom, h);
    grid.bin(x);
    NeighborList nl;
    build_neighbor_list(x, dom, WendlandC2(h), list_grid, nl);
    const auto from_list = visited(HostNeighbors{&nl, &list_grid, h * h}, x);
    const auto from_grid = visited(HostNeighbors{nullptr, &grid, h * h}, x);
    std::size_t pairs = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(from_list[i], from_grid[i]) << "particle " << i << (periodic ? " (periodic)" : "");
      for (const std::uint32_t j : from_grid[i]) {
        EXPECT_NE(j, i);
        EXPECT_LT(norm(dom.separation(x[i], x[j])), h);
      }
      pairs += from_grid[i].size();
    }
    EXPECT_EQ(pairs, nl.pair_count());
    EXPECT_GT(pairs, 4 * x.size()) << "particles with neighbours";
  }
}
