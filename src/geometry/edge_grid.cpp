#include "edge_grid.hpp"

#include <algorithm>
#include <cmath>

namespace particula::geometry_detail {

namespace {

Vec2 outward(Vec2 a, Vec2 b) {  // right of a -> b: out of a solid on the left
  const Vec2 t = b - a;
  const real n = norm(t);
  return n > 0 ? Vec2{t.y / n, -t.x / n} : Vec2{0, 0};
}

}  // namespace

EdgeGrid::EdgeGrid(const std::vector<std::vector<Vec2>>& loops) {
  Vec2 hi;
  bool first = true;
  real length = 0;
  for (const auto& loop : loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 prev = loop[(i + n - 1) % n], a = loop[i], b = loop[(i + 1) % n], next = loop[(i + 2) % n];
      const Vec2 ne = outward(a, b);
      edges_.push_back({a, b, ne + outward(prev, a), ne + outward(b, next)});
      length += norm(b - a);
      if (first) lo_ = hi = a, first = false;
      lo_ = {std::min(lo_.x, a.x), std::min(lo_.y, a.y)};
      hi = {std::max(hi.x, a.x), std::max(hi.y, a.y)};
    }
  }
  // Cells about two mean edge lengths wide: a few edges per cell along the boundary.
  const Vec2 span = hi - lo_;
  cell_ = std::max({2 * length / static_cast<real>(edges_.size()), 1e-3 * std::max(span.x, span.y)});
  nx_ = std::max(1, static_cast<int>(std::ceil(span.x / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil(span.y / cell_)) + 1);
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(nx_) * ny_);
  for (std::uint32_t e = 0; e < edges_.size(); ++e) {
    const Vec2 a = edges_[e].a, b = edges_[e].b;
    const int x0 = static_cast<int>((std::min(a.x, b.x) - lo_.x) / cell_), x1 = static_cast<int>((std::max(a.x, b.x) - lo_.x) / cell_);
    const int y0 = static_cast<int>((std::min(a.y, b.y) - lo_.y) / cell_), y1 = static_cast<int>((std::max(a.y, b.y) - lo_.y) / cell_);
    for (int y = std::max(0, y0); y <= std::min(ny_ - 1, y1); ++y)
      for (int x = std::max(0, x0); x <= std::min(nx_ - 1, x1); ++x) cells[static_cast<std::size_t>(y) * nx_ + x].push_back(e);
  }
  start_.assign(cells.size() + 1, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) start_[c + 1] = start_[c] + static_cast<std::uint32_t>(cells[c].size());
  for (const auto& c : cells) items_.insert(items_.end(), c.begin(), c.end());
}

void EdgeGrid::test_edge(const Edge& e, Vec2 p, real& best2, PolygonNearest& out) const {
  const Vec2 ab = e.b - e.a;
  const real L2 = norm2(ab);
  const real s = L2 > 0 ? std::clamp(dot(p - e.a, ab) / L2, 0.0, 1.0) : 0.0;
  const Vec2 q = e.a + s * ab;
  const real d2 = norm2(p - q);
  if (d2 >= best2) return;
  best2 = d2;
  out.point = q;
  // The side: the edge's own where q is inside it, the vertex pseudo-normal at an end (exact for
  // the nearest point of a closed loop, as for the walls' fluid region).
  const Vec2 n = s <= 0 ? e.pseudo_a : s >= 1 ? e.pseudo_b : outward(e.a, e.b);
  out.inside = dot(p - q, n) < 0;
}

PolygonNearest EdgeGrid::nearest(Vec2 p) const {
  PolygonNearest out;
  real best2 = 1e300;
  const int cx = static_cast<int>(std::floor((p.x - lo_.x) / cell_)), cy = static_cast<int>(std::floor((p.y - lo_.y) / cell_));
  // Rings of cells round p's (possibly virtual) cell, outward: an edge not yet tested lies
  // wholly outside the block of rings 0..r, so at least r cells from p.
  const int rings = std::max({cx + 1, nx_ - cx, cy + 1, ny_ - cy});
  for (int r = 0; r <= rings; ++r) {
    for (int y = cy - r; y <= cy + r; ++y) {
      if (y < 0 || y >= ny_) continue;
      const bool edge_row = y == cy - r || y == cy + r;
      for (int x = cx - r; x <= cx + r; x += edge_row ? 1 : 2 * r) {
        if (x >= 0 && x < nx_) {
          const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
          for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) test_edge(edges_[items_[k]], p, best2, out);
        }
        if (r == 0) break;
      }
    }
    const real reach = r * cell_;
    if (best2 <= reach * reach) break;
  }
  out.distance = std::sqrt(best2);
  return out;
}

}  // namespace particula::geometry_detail
