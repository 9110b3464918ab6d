// A uniform grid over the edges of a polygon (outline and holes), so that the nearest point of
// a polygon of many edges (a 126-gon ring, a digitised outline) costs the edges of a few cells
// rather than all of them. Internal to src/geometry (Shape).
#pragma once

#include <cstdint>
#include <vector>

#include "particula/core/types.hpp"

namespace particula::geometry_detail {

/// The nearest point of the polygon's boundary and the side p is on.
struct PolygonNearest {
  Vec2 point;
  real distance = 0;
  bool inside = false;  // p lies in the solid
};

class EdgeGrid {
 public:
  /// `loops`: closed loops with the solid on the left of each (outline counter-clockwise, holes
  /// clockwise).
  explicit EdgeGrid(const std::vector<std::vector<Vec2>>& loops);
  PolygonNearest nearest(Vec2 p) const;

 private:
  struct Edge {
    Vec2 a, b;
    Vec2 pseudo_a, pseudo_b;  // outward pseudo-normals at a and b: the sum of the two edges' normals
  };
  std::vector<Edge> edges_;
  Vec2 lo_;
  real cell_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_, items_;  // edges of cell c: items_[start_[c] .. start_[c + 1])

  void test_edge(const Edge& e, Vec2 p, real& best2, PolygonNearest& out) const;
};

}  // namespace particula::geometry_detail
