// BodyCells: the bodies that can come within reach of a point are found, each once.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "particula/neighbors/body_cells.hpp"

using namespace particula;

namespace {

std::vector<BodyCells::Item> random_items(const Domain& dom, int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> ux(dom.lo.x, dom.hi.x), uy(dom.lo.y, dom.hi.y);
  std::vector<BodyCells::Item> items;
  for (int k = 0; k < n; ++k) items.push_back({static_cast<std::uint32_t>(3 * k + 1), Vec2{ux(rng), uy(rng)}});
  return items;
}

/// Every body within `width` of each query point is visited, and none twice.
void expect_complete(const Domain& dom, real width, int bodies, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const auto items = random_items(dom, bodies, rng);
  BodyCells cells;
  cells.build(dom, width, items);
  // queries inside the box and up to a cell width beyond its edges
  std::uniform_real_distribution<double> qx(dom.lo.x - width, dom.hi.x + width), qy(dom.lo.y - width, dom.hi.y + width);
  for (int q = 0; q < 400; ++q) {
    const Vec2 x{qx(rng), qy(rng)};
    std::vector<int> seen(3 * bodies + 1, 0);
    cells.visit(x, [&](std::uint32_t id) {
      ++seen[id];
      return true;
    });
    for (const auto& it : items) {
      EXPECT_LE(seen[it.id], 1) << "body " << it.id << " visited twice from (" << x.x << ", " << x.y << ")";
      if (norm(dom.separation(x, it.centre)) <= width) {
        EXPECT_EQ(seen[it.id], 1) << "body " << it.id << " within reach of (" << x.x << ", " << x.y << ") missed";
      }
    }
  }
}

}  // namespace

TEST(BodyCells, FindsEveryBodyWithinTheCellWidthInABoundedBox) {
  expect_complete(Domain{{0, 0}, {1.0, 0.6}, false, false}, 0.07, 300, 11);
}

TEST(BodyCells, FindsThemAcrossPeriodicSides) {
  expect_complete(Domain{{-0.5, 0}, {0.5, 0.4}, true, true}, 0.05, 300, 12);
}

TEST(BodyCells, VisitsEachCellOnceWhereTheGridIsNarrowerThanThreeCells) {
  // 2 cells along x and 1 along y, both periodic: the 3 x 3 neighbourhood wraps onto itself
  expect_complete(Domain{{0, 0}, {1.0, 0.3}, true, true}, 0.45, 40, 13);
}

TEST(BodyCells, StopsWhenTheCallbackSaysSo) {
  const Domain dom{{0, 0}, {1, 1}, false, false};
  std::vector<BodyCells::Item> items;
  for (std::uint32_t k = 0; k < 10; ++k) items.push_back({k, Vec2{0.5, 0.5}});
  BodyCells cells;
  cells.build(dom, 0.2, items);
  std::vector<std::uint32_t> got;
  cells.visit({0.5, 0.5}, [&](std::uint32_t id) {
    got.push_back(id);
    return got.size() < 3;
  });
  // the first three in their binned order (the order given, within a cell)
  EXPECT_EQ(got, (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(BodyCells, AnEmptyGridVisitsNothing) {
  BodyCells cells;
  cells.build(Domain{{0, 0}, {1, 1}, false, false}, 0.1, {});
  EXPECT_TRUE(cells.empty());
  int calls = 0;
  cells.visit({0.5, 0.5}, [&](std::uint32_t) { return ++calls > 0; });
  EXPECT_EQ(calls, 0);
}
