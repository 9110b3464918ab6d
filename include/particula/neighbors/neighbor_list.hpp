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

/// Uniform grid of square-ish cells of side >= h covering the domain. Along a periodic axis
/// the cell count is floor(L/h) (at least 3, so the 3 neighbouring cells are distinct);
/// along a bounded axis one extra cell on each side catches particles slightly outside.
class CellGrid {
 public:
  void setup(const Domain& domain, real h);
  /// Sorts particles [first, n) by cell (counting sort) and fills `order` with the sorted
  /// indices; `cell_of` is refreshed for all n particles.
  void bin(const std::vector<Vec2>& x);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int cell_index(Vec2 p) const;
  /// Particles of cell c are sorted_[start_[c] .. start_[c+1]).
  const std::vector<std::uint32_t>& sorted() const { return sorted_; }
  const std::vector<std::uint32_t>& cell_start() const { return start_; }
  const std::vector<std::uint32_t>& cell_of() const { return cell_of_; }
  /// The up-to-9 distinct cells around cell c (fewer at bounded edges).
  int neighbor_cells(int c, int out[9]) const;

 private:
  Domain domain_;
  Vec2 origin_;
  real cell_x_ = 1, cell_y_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_, sorted_, cell_of_, fill_;
};

struct NeighborList {
  std::vector<std::uint32_t> start;  // size n+1; pairs of i are [start[i], start[i+1])
  std::vector<std::uint32_t> j;
  real min_distance = 0;             // smallest |r_ij| over all pairs (d_min of P.29-P.31)

  std::size_t size() const { return start.empty() ? 0 : start.size() - 1; }
  std::size_t pair_count() const { return j.size(); }
};

/// Builds the pair list of all particles (every pair stored from both sides, i != j,
/// r_ij < h), neighbours of each i in a fixed, thread-count independent order.
void build_neighbor_list(const std::vector<Vec2>& x, const Domain& domain, const WendlandC2& kernel,
                         CellGrid& grid, NeighborList& out);

}  // namespace particula
