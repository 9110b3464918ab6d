// Cell-linked-list neighbour search with periodic images, producing a compressed pair list
// (CSR) of neighbour indices only. Positions are frozen during the two stages of a step, so the
// list is built once per step and reused by every sweep; the sweeps recompute r_ij, |r_ij| and
// W'/r from the positions (solver/sweeps.hpp: pair_geometry), which costs a few flops per pair
// but saves streaming 32 bytes per pair from memory in every sweep.
#pragma once

#include <cstdint>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

/// Geometry of the uniform cell grid (cells of side >= h covering the domain) in D dimensions, as
/// a plain struct usable on the host and on the device. Along a periodic axis the cell count is
/// floor(L/h) (at least 3, so the 3 neighbouring cells are distinct); along a bounded axis one
/// extra cell on each side catches particles slightly outside. kCells: the most cells round a
/// cell (3^D).
template <int D>
struct GridGeometryOf;

/// The n cells of `cells` (in visit order) as runs of consecutive indices: run r is the cells
/// first[r] .. last[r]. Returns the number of runs.
PARTICULA_HD int cell_runs(const int* cells, int n, int* first, int* last) {
  int runs = 0;
  for (int m = 0; m < n; ++m) {
    if (runs > 0 && cells[m] == last[runs - 1] + 1) {
      last[runs - 1] = cells[m];
    } else {
      first[runs] = last[runs] = cells[m];
      ++runs;
    }
  }
  return runs;
}

template <>
struct GridGeometryOf<2> {
  static constexpr int kCells = 9;
  Domain domain;
  Vec2 origin;
  real cell_x = 1, cell_y = 1;
  int nx = 1, ny = 1;

  PARTICULA_HD int cell_count() const { return nx * ny; }

  PARTICULA_HD int cell_index(Vec2 p) const {
    int cx = static_cast<int>(std::floor((p.x - origin.x) / cell_x));
    int cy = static_cast<int>(std::floor((p.y - origin.y) / cell_y));
    // Clamping is 1-Lipschitz in cell index, so two particles within h of each other stay in
    // the same or adjacent cells even when one has strayed outside the grid.
    cx = cx < 0 ? 0 : (cx > nx - 1 ? nx - 1 : cx);
    cy = cy < 0 ? 0 : (cy > ny - 1 ? ny - 1 : cy);
    return cy * nx + cx;
  }

  /// The up-to-9 distinct cells around cell c (fewer at bounded edges), in a fixed order.
  PARTICULA_HD int neighbor_cells(int c, int out[9]) const {
    const int cx = c % nx, cy = c / nx;
    int k = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      int y = cy + dy;
      if (domain.periodic_y)
        y = (y + ny) % ny;
      else if (y < 0 || y >= ny)
        continue;
      for (int dx = -1; dx <= 1; ++dx) {
        int xx = cx + dx;
        if (domain.periodic_x)
          xx = (xx + nx) % nx;
        else if (xx < 0 || xx >= nx)
          continue;
        out[k++] = y * nx + xx;
      }
    }
    return k;
  }

  /// The cells of neighbor_cells(c), in the same order, as runs of consecutive cell indices:
  /// run r is cells first[r] .. last[r]. A row's three cells are one run unless a periodic
  /// wrap splits it, so a neighbour visit walks 3 contiguous stretches of the cell-sorted
  /// particles instead of 9.
  PARTICULA_HD int neighbor_cell_runs(int c, int first[9], int last[9]) const {
    int cells[9];
    return cell_runs(cells, neighbor_cells(c, cells), first, last);
  }
};
using GridGeometry = GridGeometryOf<2>;

template <>
struct GridGeometryOf<3> {
  static constexpr int kCells = 27;
  Domain3 domain;
  Vec3 origin;
  real cell_x = 1, cell_y = 1, cell_z = 1;
  int nx = 1, ny = 1, nz = 1;

  PARTICULA_HD int cell_count() const { return nx * ny * nz; }

  PARTICULA_HD int cell_index(Vec3 p) const {
    int cx = static_cast<int>(std::floor((p.x - origin.x) / cell_x));
    int cy = static_cast<int>(std::floor((p.y - origin.y) / cell_y));
    int cz = static_cast<int>(std::floor((p.z - origin.z) / cell_z));
    cx = cx < 0 ? 0 : (cx > nx - 1 ? nx - 1 : cx);  // clamped, as in 2D
    cy = cy < 0 ? 0 : (cy > ny - 1 ? ny - 1 : cy);
    cz = cz < 0 ? 0 : (cz > nz - 1 ? nz - 1 : cz);
    return (cz * ny + cy) * nx + cx;
  }

  /// The up-to-27 distinct cells around cell c (fewer at bounded edges), z outermost, x innermost.
  PARTICULA_HD int neighbor_cells(int c, int out[27]) const {
    const int cx = c % nx, cy = (c / nx) % ny, cz = c / (nx * ny);
    int k = 0;
    for (int dz = -1; dz <= 1; ++dz) {
      int z = cz + dz;
      if (domain.periodic_z)
        z = (z + nz) % nz;
      else if (z < 0 || z >= nz)
        continue;
      for (int dy = -1; dy <= 1; ++dy) {
        int y = cy + dy;
        if (domain.periodic_y)
          y = (y + ny) % ny;
        else if (y < 0 || y >= ny)
          continue;
        for (int dx = -1; dx <= 1; ++dx) {
          int xx = cx + dx;
          if (domain.periodic_x)
            xx = (xx + nx) % nx;
          else if (xx < 0 || xx >= nx)
            continue;
          out[k++] = (z * ny + y) * nx + xx;
        }
      }
    }
    return k;
  }

  /// The cells of neighbor_cells(c) as runs of consecutive cell indices (9 rows of 3 unless a
  /// periodic wrap splits one).
  PARTICULA_HD int neighbor_cell_runs(int c, int first[27], int last[27]) const {
    int cells[27];
    return cell_runs(cells, neighbor_cells(c, cells), first, last);
  }
};
using GridGeometry3 = GridGeometryOf<3>;

/// Calls consider(j, d2) for every candidate j of particle i (i itself included): the particles
/// of i's 3x3 (3x3x3) cells, in a fixed order (cells in neighbor_cells order, particles in cell
/// order). `sorted` lists particle indices cell by cell, cell c being
/// sorted[cell_start[c] .. cell_start[c+1]).
template <int D, class Consider>
PARTICULA_HD void visit_candidates(const GridGeometryOf<D>& g, const Vec<D>* x, const std::uint32_t* sorted,
                                   const std::uint32_t* cell_start, std::uint32_t cell_of_i, std::uint32_t i,
                                   Consider&& consider) {
  int first[GridGeometryOf<D>::kCells], last[GridGeometryOf<D>::kCells];
  const int runs = g.neighbor_cell_runs(static_cast<int>(cell_of_i), first, last);
  const Vec<D> xi = x[i];
  for (int r = 0; r < runs; ++r)
    for (std::uint32_t s = cell_start[first[r]]; s < cell_start[last[r] + 1]; ++s) {
      const std::uint32_t j = sorted[s];
      consider(j, norm2(g.domain.separation(xi, x[j])));
    }
}

/// Whether candidate j of particle i is a neighbour: j != i and |r_ij|^2 = d2 < h2.
PARTICULA_HD bool is_neighbor(std::uint32_t i, std::uint32_t j, real d2, real h2) {
  return (j != i) & (d2 < h2);
}

/// Calls emit(j, d2) for every neighbour j of particle i (is_neighbor), in the order of
/// visit_candidates, so the list and every sum over it are independent of the thread count and
/// identical on the CPU and the GPU.
template <int D, class Emit>
PARTICULA_HD void visit_neighbors(const GridGeometryOf<D>& g, real h2, const Vec<D>* x,
                                  const std::uint32_t* sorted, const std::uint32_t* cell_start,
                                  std::uint32_t cell_of_i, std::uint32_t i, Emit&& emit) {
  visit_candidates(g, x, sorted, cell_start, cell_of_i, i, [&](std::uint32_t j, real d2) {
    if (is_neighbor(i, j, d2, h2)) emit(j, d2);
  });
}

/// The cell grid with its particle binning (host side), in D dimensions (`CellGrid` the 2D one).
template <int D>
class CellGridOf {
 public:
  /// Cells of side h (at least 3 along a periodic axis); along a bounded axis one more cell on
  /// each side, and enough more to hold particles up to `margin` outside the domain.
  void setup(const DomainOf<D>& domain, real h, real margin = 0);
  /// Bins all particles by cell (counting sort, stable in particle index).
  void bin(const std::vector<Vec<D>>& x);

  const GridGeometryOf<D>& geometry() const { return geo_; }
  int nx() const { return geo_.nx; }
  int ny() const { return geo_.ny; }
  int cell_index(Vec<D> p) const { return geo_.cell_index(p); }
  /// Particles of cell c are sorted_[start_[c] .. start_[c+1]).
  const std::vector<std::uint32_t>& sorted() const { return sorted_; }
  const std::vector<std::uint32_t>& cell_start() const { return start_; }
  const std::vector<std::uint32_t>& cell_of() const { return cell_of_; }
  int neighbor_cells(int c, int out[GridGeometryOf<D>::kCells]) const { return geo_.neighbor_cells(c, out); }
  /// Most particles in one cell at the last binning.
  std::size_t max_occupancy() const { return max_occupancy_; }

 private:
  GridGeometryOf<D> geo_;
  std::vector<std::uint32_t> start_, sorted_, cell_of_, fill_;
  std::size_t max_occupancy_ = 0;
};
using CellGrid = CellGridOf<2>;
using CellGrid3 = CellGridOf<3>;

struct NeighborList {
  std::vector<std::uint32_t> start;  // size n+1; pairs of i are [start[i], start[i+1])
  std::vector<std::uint32_t> j;
  real min_distance = 0;  // smallest |r_ij| over all pairs (d_min of P.29-P.31)
  // Per-thread pair buffers of the one-pass build, kept between builds so that a step
  // allocates nothing once they have grown.
  std::vector<std::vector<std::uint32_t>> thread_pairs;
  std::vector<std::size_t> thread_offset;

  std::size_t size() const { return start.empty() ? 0 : start.size() - 1; }
  std::size_t pair_count() const { return j.size(); }
};

/// The neighbours of every particle at one set of host positions x, as the host reads them: the
/// rows of a neighbour list built at x, or, without one, a cell grid binned at x visited with
/// visit_neighbors. Both give the same neighbours in the same order (the list is built in that
/// visit's order).
struct HostNeighbors {
  const NeighborList* list = nullptr;
  const CellGrid* grid = nullptr;
  real h2 = 0;  // the support radius squared (for the grid's visit)

  /// Calls emit(j) for every neighbour j of particle i.
  template <class Emit>
  void visit(const Vec2* x, std::uint32_t i, Emit&& emit) const {
    if (list != nullptr) {
      for (std::uint32_t q = list->start[i]; q < list->start[i + 1]; ++q) emit(list->j[q]);
      return;
    }
    visit_neighbors(grid->geometry(), h2, x, grid->sorted().data(), grid->cell_start().data(),
                    grid->cell_of()[i], i, [&](std::uint32_t j, real) { emit(j); });
  }
};

/// Builds the pair list of all particles (every pair stored from both sides, i != j,
/// r_ij < h), neighbours of each i in a fixed, thread-count independent order (D = 2 or 3).
template <int D>
void build_neighbor_list(const std::vector<Vec<D>>& x, const DomainOf<D>& domain, const Wendland<D>& kernel,
                         CellGridOf<D>& grid, NeighborList& out);

}  // namespace particula
