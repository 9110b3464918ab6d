#include "particula/neighbors/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace particula {

void CellGrid::setup(const Domain& domain, real h) {
  geo_ = GridGeometry{};
  geo_.domain = domain;
  const Vec2 L = domain.size();
  auto axis = [&](bool periodic, real len, real lo, int& n, real& cell, real& origin) {
    if (periodic) {
      n = static_cast<int>(std::floor(len / h));
      if (n < 3) throw std::invalid_argument("periodic axis shorter than 3 kernel radii");
      cell = len / n;
      origin = lo;
    } else {
      n = std::max(1, static_cast<int>(std::ceil(len / h))) + 2;
      cell = h;
      origin = lo - h;
    }
  };
  axis(domain.periodic_x, L.x, domain.lo.x, geo_.nx, geo_.cell_x, geo_.origin.x);
  axis(domain.periodic_y, L.y, domain.lo.y, geo_.ny, geo_.cell_y, geo_.origin.y);
}

void CellGrid::bin(const std::vector<Vec2>& x) {
  const std::size_t n = x.size();
  const std::size_t ncell = static_cast<std::size_t>(geo_.cell_count());
  cell_of_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) cell_of_[i] = static_cast<std::uint32_t>(geo_.cell_index(x[i]));
  start_.assign(ncell + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++start_[cell_of_[i] + 1];
  for (std::size_t c = 0; c < ncell; ++c) start_[c + 1] += start_[c];
  sorted_.resize(n);
  fill_.assign(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) sorted_[fill_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
}

void build_neighbor_list(const std::vector<Vec2>& x, const Domain& domain, const WendlandC2& kernel,
                         CellGrid& grid, NeighborList& out) {
  (void)domain;  // the grid carries it
  const std::size_t n = x.size();
  grid.bin(x);
  const real h2 = kernel.h * kernel.h;
  const GridGeometry& geo = grid.geometry();
  const std::uint32_t* sorted = grid.sorted().data();
  const std::uint32_t* cstart = grid.cell_start().data();
  const std::uint32_t* cell_of = grid.cell_of().data();
  const Vec2* xp = x.data();

  out.start.assign(n + 1, 0);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t count = 0;
    visit_neighbors(geo, h2, xp, sorted, cstart, cell_of[i], static_cast<std::uint32_t>(i),
                    [&](std::uint32_t, real) { ++count; });
    out.start[i + 1] = count;
  }
  for (std::size_t i = 0; i < n; ++i) out.start[i + 1] += out.start[i];
  const std::size_t np = out.start[n];
  out.j.resize(np);
  real dmin2 = std::numeric_limits<real>::infinity();
#pragma omp parallel for schedule(static) reduction(min : dmin2)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t p = out.start[i];
    visit_neighbors(geo, h2, xp, sorted, cstart, cell_of[i], static_cast<std::uint32_t>(i), [&](std::uint32_t j, real d2) {
      out.j[p++] = j;
      dmin2 = std::min(dmin2, d2);
    });
  }
  out.min_distance = std::sqrt(dmin2);
}

}  // namespace particula
