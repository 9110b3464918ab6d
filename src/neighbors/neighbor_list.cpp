#include "particula/neighbors/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace particula {

void CellGrid::setup(const Domain& domain, real h) {
  domain_ = domain;
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
  axis(domain.periodic_x, L.x, domain.lo.x, nx_, cell_x_, origin_.x);
  axis(domain.periodic_y, L.y, domain.lo.y, ny_, cell_y_, origin_.y);
}

int CellGrid::cell_index(Vec2 p) const {
  int cx = static_cast<int>(std::floor((p.x - origin_.x) / cell_x_));
  int cy = static_cast<int>(std::floor((p.y - origin_.y) / cell_y_));
  // Clamping is 1-Lipschitz in cell index, so two particles within h of each other stay in
  // the same or adjacent cells even when one has strayed outside the grid.
  cx = std::clamp(cx, 0, nx_ - 1);
  cy = std::clamp(cy, 0, ny_ - 1);
  return cy * nx_ + cx;
}

void CellGrid::bin(const std::vector<Vec2>& x) {
  const std::size_t n = x.size();
  const std::size_t ncell = static_cast<std::size_t>(nx_) * ny_;
  cell_of_.resize(n);
  start_.assign(ncell + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    cell_of_[i] = static_cast<std::uint32_t>(cell_index(x[i]));
    ++start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) start_[c + 1] += start_[c];
  sorted_.resize(n);
  fill_.assign(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) sorted_[fill_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
}

int CellGrid::neighbor_cells(int c, int out[9]) const {
  const int cx = c % nx_, cy = c / nx_;
  int k = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    int y = cy + dy;
    if (domain_.periodic_y) y = (y + ny_) % ny_;
    else if (y < 0 || y >= ny_) continue;
    for (int dx = -1; dx <= 1; ++dx) {
      int xx = cx + dx;
      if (domain_.periodic_x) xx = (xx + nx_) % nx_;
      else if (xx < 0 || xx >= nx_) continue;
      out[k++] = y * nx_ + xx;
    }
  }
  return k;
}

void build_neighbor_list(const std::vector<Vec2>& x, const Domain& domain, const WendlandC2& kernel,
                         CellGrid& grid, NeighborList& out) {
  const std::size_t n = x.size();
  grid.bin(x);
  const real h2 = kernel.h * kernel.h;
  const auto& sorted = grid.sorted();
  const auto& cstart = grid.cell_start();
  const auto& cell_of = grid.cell_of();

  // Visits the neighbours of i in a fixed order (cells in neighbor_cells order, particles in
  // cell order), so the list and every sum over it are independent of the thread count.
  auto visit = [&](std::size_t i, auto&& emit) {
    int cells[9];
    const int nc = grid.neighbor_cells(static_cast<int>(cell_of[i]), cells);
    for (int k = 0; k < nc; ++k)
      for (std::uint32_t s = cstart[cells[k]]; s < cstart[cells[k] + 1]; ++s) {
        const std::uint32_t jj = sorted[s];
        if (jj == i) continue;
        const Vec2 d = domain.separation(x[i], x[jj]);
        const real d2 = norm2(d);
        if (d2 < h2) emit(jj, d, d2);
      }
  };

  out.start.assign(n + 1, 0);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t count = 0;
    visit(i, [&](std::uint32_t, Vec2, real) { ++count; });
    out.start[i + 1] = count;
  }
  for (std::size_t i = 0; i < n; ++i) out.start[i + 1] += out.start[i];
  const std::size_t np = out.start[n];
  out.j.resize(np);
  real dmin2 = std::numeric_limits<real>::infinity();
#pragma omp parallel for schedule(static) reduction(min : dmin2)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t p = out.start[i];
    visit(i, [&](std::uint32_t jj, Vec2, real d2) {
      out.j[p] = jj;
      dmin2 = std::min(dmin2, d2);
      ++p;
    });
  }
  out.min_distance = std::sqrt(dmin2);
}

}  // namespace particula
