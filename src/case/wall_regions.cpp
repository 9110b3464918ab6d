// The fluid sides of closed chains of walls must agree: a closed chain (a loop of walls joined
// head to tail, not through a periodic side) says on which side of it the fluid lies, inside
// (listed counter-clockwise, a container) or outside (clockwise, an obstacle). Where loops are
// nested, or stand in the region the other walls enclose, every region between them must be
// the same kind, fluid or solid, by all the walls that bound it.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "internal.hpp"
#include "particula/scene/scene.hpp"

namespace particula::case_detail {

namespace {

/// A loop of walls: their indexes in chain order, the loop as a polygon (arcs sampled), its
/// orientation and area, and a point on it.
struct Loop {
  std::vector<std::size_t> walls;
  std::vector<Vec2> polygon;
  bool fluid_inside = false;  // counter-clockwise
  real area = 0;
  Vec2 point;  // the middle of its first wall
};

/// The wall whose `from` is wall k's `to`, joined directly (not through a periodic side).
std::optional<std::size_t> next_wall(const Case& c, std::size_t k) {
  const real tol = 1e-6 * c.d0;
  for (std::size_t o = 0; o < c.walls.size(); ++o)
    if (norm(c.walls[o].piece().start() - c.walls[k].piece().end()) <= tol) return o;
  return std::nullopt;
}

/// The loop through wall k, if the chain starting there comes back to it directly.
std::optional<Loop> loop_through(const Case& c, std::size_t k) {
  Loop loop;
  std::optional<std::size_t> w = k;
  do {
    loop.walls.push_back(*w);
    w = next_wall(c, *w);
  } while (w && *w != k && loop.walls.size() <= c.walls.size());
  if (!w || *w != k) return std::nullopt;
  for (const std::size_t i : loop.walls) {
    const WallPiece p = c.walls[i].piece();
    const int n = p.is_arc() ? static_cast<int>(std::max(64.0, std::ceil(p.length() / (0.25 * c.d0)))) : 1;
    for (int q = 0; q < n; ++q) loop.polygon.push_back(p.point_at(static_cast<real>(q) / n));
  }
  for (std::size_t q = 0; q < loop.polygon.size(); ++q)
    loop.area += 0.5 * cross(loop.polygon[q], loop.polygon[(q + 1) % loop.polygon.size()]);
  loop.fluid_inside = loop.area > 0;
  loop.area = std::fabs(loop.area);
  loop.point = c.walls[k].piece().point_at(0.5);
  return loop;
}

/// Every loop of the case, each once (found from its wall of lowest index).
std::vector<Loop> case_loops(const Case& c) {
  std::vector<Loop> loops;
  std::vector<bool> seen(c.walls.size(), false);
  for (std::size_t k = 0; k < c.walls.size(); ++k) {
    if (seen[k]) continue;
    if (auto loop = loop_through(c, k)) {
      for (const std::size_t i : loop->walls) seen[i] = true;
      loops.push_back(std::move(*loop));
    }
  }
  return loops;
}

/// Whether p lies inside the polygon (winding number; p is not on it).
bool encloses(const std::vector<Vec2>& poly, Vec2 p) {
  int winding = 0;
  for (std::size_t q = 0; q < poly.size(); ++q) {
    const Vec2 a = poly[q], b = poly[(q + 1) % poly.size()];
    const real side = cross(b - a, p - a);
    if (a.y <= p.y && b.y > p.y && side > 0) ++winding;
    if (a.y > p.y && b.y <= p.y && side < 0) --winding;
  }
  return winding != 0;
}

/// "the closed chain of wall 'a' (wall[0]), wall 'b' (wall[1]), ... (fluid inside: counter-clockwise)".
std::string loop_text(const Case& c, const Loop& l) {
  std::vector<std::string> names;
  for (const std::size_t k : l.walls) names.push_back(wall_text(c, k));
  return fmt::format("the closed chain of {} ({})", fmt::join(names, ", "),
                     l.fluid_inside ? "fluid inside: counter-clockwise" : "fluid outside: clockwise");
}

const char* kind(bool fluid) { return fluid ? "fluid" : "solid"; }

/// The index of the smallest loop other than `k` that encloses loop k, if any.
std::optional<std::size_t> enclosing_loop(const std::vector<Loop>& loops, std::size_t k) {
  std::optional<std::size_t> parent;
  for (std::size_t o = 0; o < loops.size(); ++o)
    if (o != k && encloses(loops[o].polygon, loops[k].point) &&
        (!parent || loops[o].area < loops[*parent].area))
      parent = o;
  return parent;
}

/// The wall of `walls` nearest to p (through periodic sides).
std::size_t nearest_wall(const Case& c, const Domain& dom, const std::vector<std::size_t>& walls, Vec2 p) {
  std::size_t best = walls.front();
  real best_distance = std::numeric_limits<real>::infinity();
  for (const std::size_t k : walls) {
    const WallPiece w = c.walls[k].piece();
    const real d = w.nearest(w.middle() + dom.separation(p, w.middle())).distance;
    if (d < best_distance) best_distance = d, best = k;
  }
  return best;
}

}  // namespace

/// Loop B directly inside loop A: the region between them is A's inside and B's outside, so B
/// must turn the other way (a container round obstacles, an obstacle round a pocket of fluid).
/// A loop inside no other stands in the region the other walls (chains ending on the domain's
/// edge or closing through a periodic side) enclose, or, without such walls, beside the other
/// outermost loops: its outside must be the kind that region is.
void check_wall_regions(const Case& c, const LoadContext& ctx) {
  const std::vector<Loop> loops = case_loops(c);
  std::vector<bool> in_loop(c.walls.size(), false);
  for (const Loop& l : loops)
    for (const std::size_t k : l.walls) in_loop[k] = true;
  std::vector<std::size_t> others;
  std::vector<WallPiece> other_pieces;
  for (std::size_t k = 0; k < c.walls.size(); ++k)
    if (!in_loop[k]) others.push_back(k), other_pieces.push_back(c.walls[k].piece());
  const Domain dom{c.domain_min, c.domain_max, c.periodic_x, c.periodic_y};
  std::optional<std::size_t> first_outermost;
  for (std::size_t k = 0; k < loops.size(); ++k) {
    const Loop& inner = loops[k];
    const std::size_t w0 = inner.walls.front();
    const std::string key = wall_key(w0, c.walls[w0].shape == WallShape::Arc ? "center" : "from");
    if (const auto parent = enclosing_loop(loops, k)) {
      const Loop& outer = loops[*parent];
      if (outer.fluid_inside != inner.fluid_inside) continue;
      throw ctx.error(key,
                      fmt::format("{} lies inside {}: the region between them would be {} by the outer chain "
                                  "and {} by the inner one. Inside a container (fluid inside) an obstacle "
                                  "turns clockwise (fluid outside); inside an obstacle only a pocket of "
                                  "fluid, counter-clockwise; reverse one of the two chains",
                                  loop_text(c, inner), loop_text(c, outer), kind(outer.fluid_inside),
                                  kind(!inner.fluid_inside)));
    }
    if (!others.empty()) {
      const bool region_fluid = in_fluid_region(other_pieces, dom, inner.point);
      if (region_fluid != inner.fluid_inside) continue;
      const std::size_t w = nearest_wall(c, dom, others, inner.point);
      throw ctx.error(
          key,
          fmt::format("{} stands in the region that the walls ending on the domain's edge or "
                      "closing through a periodic side make {} (the side of {} it lies on), but "
                      "says its outside is {}; reverse the chain",
                      loop_text(c, inner), kind(region_fluid), wall_text(c, w), kind(!inner.fluid_inside)));
    }
    if (!first_outermost) {
      first_outermost = k;
      continue;
    }
    const Loop& first = loops[*first_outermost];
    if (first.fluid_inside == inner.fluid_inside) continue;
    throw ctx.error(key,
                    fmt::format("{} and {} stand side by side, inside no other chain: the region round them "
                                "would be {} by the first and {} by the second; put the obstacle (clockwise) "
                                "inside a container (counter-clockwise), or reverse one of the two chains",
                                loop_text(c, first), loop_text(c, inner), kind(!first.fluid_inside),
                                kind(!inner.fluid_inside)));
  }
}

}  // namespace particula::case_detail
