// Fixed bodies on and through walls (a block standing on the floor or sunk into it, a bump, a
// body cut by the domain's edge): the stretches of a wall inside a body, where its surface
// crosses the wall, and which points lie beyond the walls.
#include <cmath>

#include "particula/scene/scene.hpp"
#include "scene_walls.hpp"

namespace particula::scene_detail {

std::vector<std::pair<real, real>> wall_stretches(const WallPiece& wall, const std::function<bool(real)>& holds,
                                                  real d0) {
  std::vector<std::pair<real, real>> out;
  const int n = std::max(16, static_cast<int>(std::ceil(16 * wall.length() / d0)));
  bool in = holds(0);
  real start = 0;
  for (int i = 1; i <= n; ++i) {
    const real s = static_cast<real>(i) / n;
    if (holds(s) == in) continue;
    real a = static_cast<real>(i - 1) / n, b = s;  // holds(a) == in, holds(b) != in
    for (int it = 0; it < 60; ++it) {
      const real m = 0.5 * (a + b);
      (holds(m) == in ? a : b) = m;
    }
    const real edge = 0.5 * (a + b);
    if (in) out.emplace_back(start, edge);
    start = edge;
    in = !in;
  }
  if (in) out.emplace_back(start, 1);
  return out;
}

std::vector<Crossing> body_wall_crossings(const Shape& shape, Vec2 pos, real angle, const WallPiece& wall, real d0) {
  std::vector<Crossing> out;
  if (wall.nearest(pos).distance > shape.bounding_radius()) return out;  // out of the body's reach
  const real c = std::cos(angle), s = std::sin(angle);
  const auto local = [&](Vec2 x) { return rotate(x - pos, c, -s); };
  // Inside means deeper than round-off: a flat side lying on the wall (a body standing on it)
  // is not crossed. Each end of a stretch inside the body, other than the wall's own ends, is a
  // crossing.
  const real eps = 1e-6 * d0;
  const auto inside = [&](real t) { return shape.signed_distance(local(wall.point_at(t))) < -eps; };
  for (const auto& [s0, s1] : wall_stretches(wall, inside, d0))
    for (const real t : {s0, s1}) {
      if (t == 0 || t == 1) continue;
      const Vec2 x = wall.point_at(t);
      real d = 0;
      Vec2 nb;
      shape.distance_and_gradient(local(x), d, nb);
      out.push_back({x, rotate(nb, c, s), wall.normal_at(t)});
    }
  return out;
}

bool beyond_walls(Vec2 x, const std::vector<WallPiece>& walls, const Domain& dom) {
  if ((!dom.periodic_x && (x.x < dom.lo.x || x.x > dom.hi.x)) || (!dom.periodic_y && (x.y < dom.lo.y || x.y > dom.hi.y)))
    return true;
  return !walls.empty() && signed_wall_distance(walls, dom, x) < 0;
}

}  // namespace particula::scene_detail
