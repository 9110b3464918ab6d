// Fixed bodies that cross a wall (a block sunk into the floor, a bump, a body cut by the
// domain's edge): where the body's surface meets the wall.
#include <cmath>

#include "scene_walls.hpp"

namespace particula::scene_detail {

std::vector<Crossing> body_wall_crossings(const Shape& shape, Vec2 pos, real angle, const WallPiece& wall, real d0) {
  const real c = std::cos(angle), s = std::sin(angle);
  // Inside means deeper than round-off: a flat side lying on the wall (a body standing on it)
  // is not crossed.
  const real eps = 1e-6 * d0;
  const auto gap = [&](real t) { return shape.signed_distance(rotate(wall.point_at(t) - pos, c, -s)) + eps; };
  std::vector<Crossing> out;
  // Only a wall passing within the body's reach can cross it.
  if (wall.nearest(pos).distance > shape.bounding_radius()) return out;
  const int n = std::max(16, static_cast<int>(std::ceil(16 * wall.length() / d0)));
  real t0 = 0, g0 = gap(0);
  for (int i = 1; i <= n; ++i) {
    const real t1 = static_cast<real>(i) / n, g1 = gap(t1);
    if ((g0 < 0) != (g1 < 0)) {
      real a = t0, b = t1;  // bisection keeps gap(a) and gap(b) of opposite signs
      const bool a_inside = g0 < 0;
      for (int it = 0; it < 60; ++it) {
        const real m = 0.5 * (a + b);
        ((gap(m) < 0) == a_inside ? a : b) = m;
      }
      const real t = 0.5 * (a + b);
      const Vec2 x = wall.point_at(t);
      real d = 0;
      Vec2 nb;
      shape.distance_and_gradient(rotate(x - pos, c, -s), d, nb);
      out.push_back({x, rotate(nb, c, s), wall.normal_at(t)});
    }
    t0 = t1, g0 = g1;
  }
  return out;
}

}  // namespace particula::scene_detail
