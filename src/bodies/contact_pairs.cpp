#include "particula/bodies/contact_pairs.hpp"

#include <algorithm>
#include <cmath>

namespace particula {

namespace {

/// The pair test shared by both searches (bitwise the same predicate).
bool within_reach(const std::vector<Vec2>& pos, const std::vector<real>& bound, real range,
                  const Domain& domain, std::size_t i, std::size_t j) {
  return !(norm(domain.separation(pos[i], pos[j])) > bound[i] + bound[j] + range);
}

/// Cells along one axis: as many as fit at the minimum width, at least one.
int cells_along(real length, real width) {
  const real n = std::floor(length / width);
  return n >= 1 ? static_cast<int>(std::min<real>(n, 1 << 20)) : 1;
}

/// Cell coordinate of x along an axis from `lo` with `n` cells of width `w` (clamped to the box).
int cell_of(real x, real lo, real w, int n) {
  const real c = std::floor((x - lo) / w);
  return c < 0 ? 0 : (c >= n ? n - 1 : static_cast<int>(c));
}

}  // namespace

void contact_candidates_all_pairs(const std::vector<Vec2>& pos, const std::vector<real>& bound, real range,
                                  const Domain& domain, std::vector<BodyPair>& out) {
  out.clear();
  for (std::size_t i = 0; i < pos.size(); ++i)
    for (std::size_t j = i + 1; j < pos.size(); ++j)
      if (within_reach(pos, bound, range, domain, i, j))
        out.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
}

void contact_candidates(const std::vector<Vec2>& pos, const std::vector<real>& bound, real range,
                        const Domain& domain, std::vector<BodyPair>& out) {
  out.clear();
  const std::size_t n = pos.size();
  if (n < 2) return;
  real max_bound = 0;
  for (real b : bound) max_bound = std::max(max_bound, b);
  const real width = std::max<real>(2 * max_bound + range, 1e-300);
  // Cells of at least `width`; no more cells than about 4 per body (a sparse set of bodies in a
  // large box would otherwise pay for empty cells), which only widens them.
  const Vec2 L = domain.size();
  int nx = cells_along(L.x, width), ny = cells_along(L.y, width);
  const real most = 4.0 * static_cast<real>(n) + 16;
  while (static_cast<real>(nx) * ny > most) {
    nx = std::max(1, nx / 2);
    ny = std::max(1, ny / 2);
  }
  const real wx = L.x / nx, wy = L.y / ny;
  // Counting sort of the bodies by cell.
  std::vector<int> cell(n);
  std::vector<std::uint32_t> start(static_cast<std::size_t>(nx) * ny + 1, 0), order(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 x = domain.wrap(pos[i]);
    cell[i] = cell_of(x.y, domain.lo.y, wy, ny) * nx + cell_of(x.x, domain.lo.x, wx, nx);
    ++start[static_cast<std::size_t>(cell[i]) + 1];
  }
  for (std::size_t c = 0; c + 1 < start.size(); ++c) start[c + 1] += start[c];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      order[fill[static_cast<std::size_t>(cell[i])]++] = static_cast<std::uint32_t>(i);
  }
  // Each body against the bodies of its own and the 8 neighbouring cells (wrapped along periodic
  // axes; with fewer than 3 cells there a cell can be visited twice, removed below).
  for (std::size_t i = 0; i < n; ++i) {
    const int cx = cell[i] % nx, cy = cell[i] / nx;
    for (int dy = -1; dy <= 1; ++dy) {
      int y = cy + dy;
      if (y < 0 || y >= ny) {
        if (!domain.periodic_y) continue;
        y = (y + ny) % ny;
      }
      for (int dx = -1; dx <= 1; ++dx) {
        int x = cx + dx;
        if (x < 0 || x >= nx) {
          if (!domain.periodic_x) continue;
          x = (x + nx) % nx;
        }
        const std::size_t c = static_cast<std::size_t>(y) * nx + x;
        for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
          const std::size_t j = order[k];
          if (j > i && within_reach(pos, bound, range, domain, i, j))
            out.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
        }
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace particula
