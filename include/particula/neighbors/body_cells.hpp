// A uniform grid of cells over the bodies' centres, for the questions "which bodies can come
// within reach of this point": the scene's distance to the nearest body (the fluid fill) and the
// solids near each fluid particle (the load band).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "particula/neighbors/domain.hpp"

namespace particula {

class BodyCells {
 public:
  /// One body to bin: its id (returned by visit) and its centre.
  struct Item {
    std::uint32_t id;
    Vec2 centre;
  };

  /// Bins the items into cells at least `width` wide (the largest bounding radius of the bodies
  /// plus the reach of the queries): every body whose surface comes within reach of a point lies
  /// in the point's cell or one of the 8 around it. Within a cell the items keep their order.
  void build(const Domain& dom, real width, const std::vector<Item>& items);

  bool empty() const { return ids_.empty(); }

  /// Calls f(id) for the bodies of x's cell and the 8 around it (wrapped across periodic sides,
  /// each cell once where the grid is narrower than 3), row by row from below, each cell's in
  /// their binned order; stops when f returns false.
  template <class F>
  void visit(Vec2 x, F&& f) const {
    const std::size_t c0 = cell_index(x);
    const int cx0 = static_cast<int>(c0 % nx_), cy0 = static_cast<int>(c0 / nx_);
    std::size_t seen[9];
    int nseen = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int cx = cx0 + dx, cy = cy0 + dy;
        if (dom_.periodic_x) cx = (cx + nx_) % nx_;
        if (dom_.periodic_y) cy = (cy + ny_) % ny_;
        if (cx < 0 || cx >= nx_ || cy < 0 || cy >= ny_) continue;
        const std::size_t c = static_cast<std::size_t>(cy) * nx_ + cx;
        if (std::find(seen, seen + nseen, c) != seen + nseen) continue;
        seen[nseen++] = c;
        for (std::size_t q = start_[c]; q < start_[c + 1]; ++q)
          if (!f(ids_[q])) return;
      }
  }

 private:
  /// The cell of x (wrapped into the domain; clamped to the grid along a bounded axis, which
  /// keeps points within a cell width of each other in the same or adjacent cells).
  std::size_t cell_index(Vec2 x) const;

  Domain dom_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_;  // cell c's items are ids_[start_[c], start_[c + 1])
  std::vector<std::uint32_t> ids_;
};

}  // namespace particula
